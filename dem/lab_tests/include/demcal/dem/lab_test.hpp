#pragma once
// Lab tests behind one interface and a registry by name, like the contact
// models: a test declares what it measures (its outputs, with units) and the
// contact roles of its boundaries, and runs a scene. A new test is one file
// plus one line in register_builtin_tests (src/lab_test.cpp).
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "demcal/dem/specimen_roles.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

class Scene;

// A macro value a test reports.
// The values an output can take at all (a strength is never negative, a
// Poisson's ratio of a 2D assembly lies in [-1, 1]): a target outside is
// refused before any run. Infinite ends are open.
struct OutputRange {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
};
inline constexpr OutputRange kAnyValue{};
inline constexpr OutputRange kNonNegative{0.0, std::numeric_limits<double>::infinity()};
inline constexpr OutputRange kFlag{0.0, 1.0};            // 1 or 0
inline constexpr OutputRange kPoissonRatio2D{-1.0, 1.0};  // plane stress: -1 < nu < 1
inline constexpr OutputRange kAcuteAngleDeg{0.0, 90.0};
inline constexpr OutputRange kAtMostOne{-std::numeric_limits<double>::infinity(), 1.0};  // R^2

struct OutputSpec {
  std::string name, unit, description;
  bool always = true;  // false: reported only in some runs (a flag such as reached_strain_limit)
  OutputRange range = kAnyValue;
};

// A contact role of a test's boundary ("disk-platen"): it joins every group
// of the specimen to the boundary's group.
struct BoundaryRole {
  std::string name;
  std::uint8_t group = 0;
  std::string description;
};

// A scene section a test reads itself (the heap's "particles", "funnel").
struct SceneSection {
  std::string name;
  std::string description;
  bool shapes_specimen = false;  // its values make another particle set, not the same one with other contacts
};

class LabTest {
 public:
  virtual ~LabTest() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  virtual std::vector<BoundaryRole> boundary_roles() const = 0;
  // A test that makes its own particles (a heap poured from a funnel) instead
  // of loading a packed specimen names the scene sections it reads in place
  // of "specimen" and "loading", and the contact roles of its particles
  // (group 0; its boundaries join them). Empty for the tests of a packed specimen.
  virtual std::vector<SceneSection> own_sections() const { return {}; }
  virtual std::vector<ContactRole> particle_roles() const { return {}; }
  // A test of a packed specimen that reads more than "specimen" and
  // "loading" (a wave strip's "boundaries", "pulse") names those sections here.
  virtual std::vector<SceneSection> extra_sections() const { return {}; }
  // Checks the test's own (or extra) sections with the parameters' defaults at load;
  // throws an Error naming the file and field.
  virtual void check_scene(const Scene& scene) const { (void)scene; }
  // Raised when a change to this test alone changes its results (0: none
  // yet), so stored results of its scenes are run again and the other
  // tests' stay valid; enters the scene's fingerprint when nonzero.
  virtual int results_version() const { return 0; }
  // Whether every stress output scales by k when every stress-like parameter
  // does (quasi-static bonded tests: docs/explanation/calibration_method.md). False for a test
  // that gravity or inertia drives (a heap), so no calibration assumes it.
  virtual bool exact_scaling() const { return true; }
  // What a run of `scene` reports (some outputs depend on the specimen, e.g.
  // the cracks in the mortar and the interface of a concrete).
  virtual std::vector<OutputSpec> outputs(const Scene& scene) const = 0;
  // The outputs a progress line shows and a report leads with (the test's
  // headline values), and those that are moduli (set by the stiffnesses
  // alone: a calibration's preferred scale target). Names of outputs();
  // describe flags them, so the study layer keeps no list of its own.
  virtual std::vector<std::string> headline_outputs(const Scene& scene) const;
  virtual std::vector<std::string> modulus_outputs(const Scene&) const { return {}; }
  // The labels of the axes of the test's curve, for plots ({"", ""}: its record
  // is not a stress-strain curve).
  virtual std::pair<std::string, std::string> curve_axes() const { return {"axial strain", "axial stress (MPa)"}; }
  // Packs (or loads) the specimen, bonds it and runs the test. Bad input
  // throws; a run that goes unstable or times out returns ok = false.
  virtual TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                         const RunOptions& options) const = 0;
};

class LabTestRegistry {
 public:
  static LabTestRegistry& instance();  // holds the built-in tests
  void add(std::unique_ptr<LabTest> test);
  // Throws an Error "<where>: unknown test ... (known: ...)".
  const LabTest& find(const std::string& name, const std::string& where) const;
  std::vector<std::string> names() const;

 private:
  std::vector<std::unique_ptr<LabTest>> tests_;
};

// Runs the scene's lab test (LabTestRegistry) and checks that it reported
// only outputs it declares, and every output it always reports.
TestResult run_test(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// One registration function per built-in test (each in its own file).
void register_ucs_test(LabTestRegistry& registry);
void register_brazilian_test(LabTestRegistry& registry);
void register_biaxial_test(LabTestRegistry& registry);
void register_external_test(LabTestRegistry& registry);
void register_heap_test(LabTestRegistry& registry);
void register_wave_strip_test(LabTestRegistry& registry);
void register_builtin_tests(LabTestRegistry& registry);

}  // namespace demcal::dem
