#pragma once
// Lab tests behind one interface and a registry by name, like the contact
// models: a test declares what it measures (its outputs, with units), the
// scene sections it reads, its contact roles and the engine whose contact
// models it runs (2D disks or 3D spheres), and runs a scene. Nothing here
// depends on the dimension: each test's engine reads its own sections. A
// new test is one file plus one line in register_builtin_tests
// (dem/lab_tests/src/builtin_tests.cpp).
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "demcal/dem/contact_model_catalog.hpp"
#include "demcal/dem/contact_role.hpp"
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

// A contact role of a test's boundary ("particle-platen"): it joins every
// group of the specimen to the boundary's group.
struct BoundaryRole {
  std::string name;
  std::uint8_t group = 0;
  std::string description;
};

// A scene section a test reads itself ("specimen", "loading", a heap's "funnel").
struct SceneSection {
  std::string name;
  std::string description;
  bool shapes_specimen = false;  // its values make another particle set, not the same one with other contacts
  bool required = false;
  // Keys of a specimen-shaping section that act after the packing (a locked-in stress).
  std::vector<std::string> keys_not_shaping = {};
};

// A specimen a run needs packed before it starts: a batch packs each distinct
// one (by `cache_key`) once, in parallel, and the runs find it in the cache.
struct SpecimenToPack {
  std::string cache_key;
  std::function<void(const std::string& cache_dir)> pack;
};

class LabTest {
 public:
  virtual ~LabTest() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  // 2 (disks) or 3 (spheres): the engine that runs the test; 0 for a test
  // whose simulator is not ours (an external command).
  virtual int dimension() const = 0;
  // The contact models a scene of this test may name: its engine's registry.
  virtual const ContactModelCatalog& contact_models() const = 0;
  virtual std::vector<BoundaryRole> boundary_roles() const = 0;
  // The scene sections the test reads besides name, test, description,
  // parameters and contacts ("specimen", "aggregates", "loading"; a heap's
  // "particles", "funnel", "run"). A file with any other section is refused.
  virtual std::vector<SceneSection> sections() const { return {}; }
  // The contact roles of the specimen's own pairs, read from the scene's
  // sections (a concrete's aggregates add roles); the boundaries' roles join
  // every group these name.
  virtual std::vector<ContactRole> specimen_roles(const Scene& scene) const = 0;
  // Whether "loading" may hold confining stresses (the biaxial series), and
  // the elastic speed-up (uniaxial compression).
  virtual bool confined() const { return false; }
  virtual bool speeds_up_while_elastic() const { return false; }
  // Checks the test's sections with the parameters' defaults at load; throws
  // an Error naming the file and field.
  virtual void check_scene(const Scene& scene) const { (void)scene; }
  // The specimens a run at `parameters` and `seed` packs (none for a test
  // that makes its particles as it runs, or whose program packs its own).
  virtual std::vector<SpecimenToPack> specimens_to_pack(const Scene& scene,
                                                        const std::map<std::string, double>& parameters,
                                                        std::uint64_t seed) const {
    (void)scene, (void)parameters, (void)seed;
    return {};
  }
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
  static LabTestRegistry& instance();  // holds the built-in tests (register_builtin_tests)
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

// Registers every built-in test: defined where the engines' tests are linked
// (dem/lab_tests/src/builtin_tests.cpp), as ContactModelRegistry::instance()
// is by the models, so this layer depends on no engine.
void register_builtin_tests(LabTestRegistry& registry);

}  // namespace demcal::dem
