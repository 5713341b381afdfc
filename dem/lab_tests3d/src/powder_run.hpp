#pragma once
// What the 3D powder tests (heap_3d, drum_3d) share: the "particles"
// section, the Rayleigh step of their Hertz material, the world settings of
// a run (damping, a safety factor or a fixed Rayleigh fraction, threads), and
// what every result reports of its contacts (the step's share of the
// Rayleigh step, the JKR cohesion number).
#include <chrono>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/powder_3d.hpp"
#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {

inline constexpr double kPowderGravity_m_s2 = 9.81;

// The "particles" section: radius_min_m, radius_max_m, density_kg_m3 (required), clump_aspect_ratio,
// clump_fraction; solids_fraction is the caller's. Not validated here (PowderSpec3d::validate).
PowderSpec3d read_powder_section(const dem::Scene& scene, const std::map<std::string, double>& parameters);

// The time-stepping keys of a powder test's "run" section.
struct PowderStepping {
  double local_damping = 0, safety_factor = 0.8, rayleigh_fraction = 0;
  static const std::vector<std::string>& keys();  // the three keys' names
  // Reads the three keys of `run` (optional) and checks them; an Error naming the file and field.
  void read(const dem::Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& run);
};

// pi R_min sqrt(rho / G) / (0.1631 nu + 0.8766) of the particle-particle contact's Hertz material (the common
// DEM rule for Hertz contacts); 0 when that contact has no shear_modulus_pa and poisson.
double rayleigh_step_s(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                       const PowderSpec3d& powder);

// Gravity along -z, the run's damping and step (a fixed Rayleigh fraction when set), the options' threads.
WorldSettings powder_settings(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                              const PowderSpec3d& powder, const PowderStepping& stepping,
                              const dem::RunOptions& options);

// dt_over_rayleigh_step for the step the run ended with, and for JKR particles the work of adhesion and the
// cohesion number of two mean particles.
void report_powder_contacts(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                            const PowderSpec3d& powder, double dt_s, dem::TestResult& result);

// The end of a run: steps, the step it ended with (and report_powder_contacts), threads, wall times, and the
// final VTK snapshot of spheres and walls when options.vtk_dir is set.
void finish_powder_run(const World& world, const dem::Scene& scene, const std::map<std::string, double>& parameters,
                       const PowderSpec3d& powder, const dem::RunOptions& options,
                       std::chrono::steady_clock::time_point start,
                       std::chrono::steady_clock::time_point loading_start, dem::TestResult& result);

// The moving bodies' potential energy above height floor_z, J (a clump counts once, at its centre of mass).
double potential_energy_j(const World& world, double floor_z);

inline constexpr std::uint8_t kPowderGroup = 0, kPowderWallGroup = 1;

// A 3D powder test: makes its own particles (group 0) against walls (group 1), on the sphere engine's models;
// gravity sets its stresses (no exact scaling); its curve is a record of its own, not a stress-strain curve.
class PowderTest3d : public dem::LabTest {
 public:
  bool exact_scaling() const override { return false; }
  int results_version() const override { return 1; }
  int dimension() const override { return 3; }
  const dem::ContactModelCatalog& contact_models() const override;
  std::vector<dem::ContactRole> specimen_roles(const dem::Scene&) const override;
  std::pair<std::string, std::string> curve_axes() const override { return {"", ""}; }

 protected:
  // The "particles" section every powder test reads (read_powder_section).
  static dem::SceneSection particles_section() {
    return {"particles", "the powder: radii, density, two-sphere clumps", true, true};
  }
};

}  // namespace demcal::dem3d
