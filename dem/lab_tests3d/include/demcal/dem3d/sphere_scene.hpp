#pragma once
// What a 3D test reads from a scene: the sphere engine's contact models (as
// the scene layer's catalog, and bound into a World) and the packed specimen
// of the "specimen" section; and PackedSphereTest, the base of the tests of a
// packed sphere specimen, which declares those sections, the specimen's role
// and what a batch packs.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/genesis.hpp"
#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {

using dem::Scene;

// A 3D Poisson's ratio lies in (-1, 0.5).
inline constexpr dem::OutputRange kPoissonRatio3D{-1.0, 0.5};

constexpr std::uint8_t kSpecimenGroup = 0, kPlatenGroup = 1;

// The sphere engine's contact models (ContactModelRegistry) as the scene layer sees them.
const dem::ContactModelCatalog& sphere_contact_models();

// Creates a model for each of the scene's contact roles (bound to
// `parameters`, with any "friction" set to 0 when `frictionless`) and
// assigns it to the role's groups.
void bind_contact_models(World& world, const Scene& scene, const std::map<std::string, double>& parameters,
                         bool frictionless = false);

// The scene's "specimen" section at `parameters`: a cylinder (diameter_m,
// height_m) or a box (width_m, depth_m, height_m), radii, porosity, density.
SphereSpecimenSpec sphere_specimen_spec(const Scene& scene, const std::map<std::string, double>& parameters,
                                        std::uint64_t seed);

// A 3D test of a packed specimen: reads "specimen" (required) and "loading".
class PackedSphereTest : public dem::LabTest {
 public:
  int dimension() const override { return 3; }
  const dem::ContactModelCatalog& contact_models() const override { return sphere_contact_models(); }
  std::vector<dem::SceneSection> sections() const override;
  std::vector<dem::ContactRole> specimen_roles(const Scene& scene) const override;
  void check_scene(const Scene& scene) const override;
  std::vector<dem::SpecimenToPack> specimens_to_pack(const Scene& scene, const std::map<std::string, double>& parameters,
                                                     std::uint64_t seed) const override;
};

// The world settings a run's loading and options ask for (damping, safety
// factor, density scaling, threads).
WorldSettings loading_settings(const dem::LoadingSpec& loading, const dem::RunOptions& options);

// A world with the scene's contact models (friction 0 when `frictionless`)
// and the specimen's spheres (sphere k with id k), entering in the order
// options.particle_order_seed gives; `admit`, when given, may move a sphere's
// centre or leave it out (false).
World specimen_world(const Scene& scene, const std::map<std::string, double>& parameters,
                     const SphereSpecimen& specimen, const dem::RunOptions& options,
                     const std::function<bool(Vec3& centre_m, double radius_m)>& admit = {},
                     bool frictionless = false);

// Bonds the world's spheres (pairs within loading.bond_gap_tolerance_m, or 1 %
// of the smallest radius), makes the contacts with its walls (placed where
// the vessel was) force-free, and starts the test. A packing's overlaps are
// made force-free as they lie; a pressured specimen's (locked_in_stress_pa >
// 0) keep their forces, and the specimen is relaxed out of its vessel and the
// walls set back where they touch it (material_pressure.hpp): the test reads
// its platens' places from the walls. `info` receives what every 3D result
// states of its specimen. The reason when the relaxation fails; empty when
// the test can go on.
std::string bond_specimen(World& world, const Scene& scene, const SphereSpecimen& specimen, std::uint64_t seed,
                          std::map<std::string, double>& info);

// The sphere world as the loading monitor sees it: a run fails on a non-finite
// value, a sphere through a platen (walls[0] and walls[1], planes whose
// normals point into the specimen), or a sphere faster than 1000 x the platen
// speed.
class SphereMonitoredWorld : public dem::MonitoredWorld {
 public:
  explicit SphereMonitoredWorld(const World& world) : world_(world) {}
  std::string instability(double platen_velocity_m_s) const override;
  double kinetic_energy_j() const override { return world_.kinetic_energy(); }
  std::size_t breaks() const override { return world_.breaks().size(); }
  void snapshot(const dem::RunOptions& options, std::size_t points, bool final) const override;

 private:
  const World& world_;
};

// Steps, time step, threads, wall times and the crack counts by mode.
void record_run_end(const World& world, const dem::RunOptions& options, std::chrono::steady_clock::time_point start,
                    std::chrono::steady_clock::time_point loading_start, dem::TestResult& result);

}  // namespace demcal::dem3d
