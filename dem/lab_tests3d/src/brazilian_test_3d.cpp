// The Brazilian disc in 3D: a sphere cylinder (the disc, its axis along z,
// its thickness the packing's height) loaded across a diameter between two
// frictionless platens, with the 2D test's outputs: sigma_t = 2 F / (pi D t)
// at the peak force, the platens' approach at the peak over D, cracks by mode.
// As in 2D the disc is flattened where the platens bear (flats at 10 degrees
// from the loading axis, which spread the load over several spheres instead
// of crushing one), and the platens start on the flats, touching every sphere
// that crosses a flat with no force.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "demcal/core/error.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/material_pressure.hpp"
#include "demcal/dem3d/sphere_scene.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::size_t kLeft = 0, kRight = 1;  // the platens, normal to x

dem::TestResult run_brazilian_3d(const Scene& scene, const std::map<std::string, double>& parameters,
                                 const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const dem::LoadingSpec& loading = scene.loading();
  dem::TestResult result;
  SphereSpecimen disc;
  if (!test_specimen(scene, parameters, options, result, disc)) return result;
  const double D = disc.width_m, t = disc.height_m, flat = 0.5 * D * std::cos(10.0 * M_PI / 180.0);
  // A pressured disc's spheres stay where the stress left them: a moved one would load its neighbours.
  const bool grind_flats = !(disc.locked_in_stress_pa > 0);

  World world = specimen_world(scene, parameters, disc, options, [&](Vec3& centre, double r) {
    if (std::abs(centre.x) > flat) return false;  // cut off by a flat
    // A sphere crossing a flat by more than half its radius is set back to
    // half (the flats ground true); bonding makes its new overlaps force-free.
    if (grind_flats && std::abs(centre.x) > flat - 0.5 * r) centre.x = std::copysign(flat - 0.5 * r, centre.x);
    return true;
  });
  world.walls = {make_plane({-flat, 0, 0}, {1, 0, 0}, kPlatenGroup), make_plane({flat, 0, 0}, {-1, 0, 0}, kPlatenGroup)};
  result.reason = bond_specimen(world, scene, disc, options.seed, result.specimen_info);
  if (!result.reason.empty()) return result;
  result.particles = world.spheres.size();
  result.porosity = disc.porosity;

  world.walls[kLeft].velocity_m_s = {loading.platen_velocity_m_s, 0, 0};
  world.walls[kRight].velocity_m_s = {-loading.platen_velocity_m_s, 0, 0};
  // From the walls: a pressured disc's platens were set back on it after it relaxed.
  const double gap0 = world.walls[kRight].point_m.x - world.walls[kLeft].point_m.x;
  const auto loading_start = std::chrono::steady_clock::now();
  // sigma = 2 F / (pi D t) and the approach over D: F d(approach) = sigma d(approach / D) pi D^2 t / 2.
  dem::LoadingMonitor monitor(loading, options, start, 0.5 * M_PI * D * D * t);
  double next_record = 0;
  for (;;) {
    world.step();
    const double approach = (gap0 - (world.walls[kRight].point_m.x - world.walls[kLeft].point_m.x)) / D;
    if (approach < next_record) continue;
    next_record = approach + loading.record_strain;
    dem::CurvePoint point;
    point.axial_strain = approach;
    point.stress_pa =
        2.0 * 0.5 * (world.walls[kLeft].normal_force_n + world.walls[kRight].normal_force_n) / (M_PI * D * t);
    point.cracks = world.breaks().size();
    if (!monitor.record(SphereMonitoredWorld(world), point, result,
                        "platen approach " + std::to_string(approach) + " D"))
      break;
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    std::size_t peak = 0;
    for (std::size_t k = 1; k < result.curve.size(); ++k)
      if (result.curve[k].stress_pa > result.curve[peak].stress_pa) peak = k;
    result.macro["sigma_t_MPa"] = monitor.peak() / 1e6;
    result.macro["peak_approach_over_D"] = result.curve[peak].axial_strain;
  }
  return result;
}

class BrazilianTest3D : public PackedSphereTest {
 public:
  std::string name() const override { return "brazilian_3d"; }
  std::string description() const override {
    return "Brazilian disc of spheres (a cylinder of its thickness), flattened where the platens bear, split across "
           "its diameter";
  }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-platen", kPlatenGroup, "the disc's spheres against the loading platens"}};
  }
  void check_scene(const Scene& scene) const override {
    PackedSphereTest::check_scene(scene);
    if (sphere_specimen_spec(scene, scene.resolve({}), 1).vessel != Vessel::cylinder)
      throw Error(scene.origin() + ": specimen.shape: brazilian_3d loads a disc (\"shape\": \"cylinder\", its "
                                   "height_m the disc's thickness)");
  }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"sigma_t_MPa"}; }
  std::pair<std::string, std::string> curve_axes() const override {
    return {"platen approach / D", "2F / (pi D t) (MPa)"};
  }
  std::vector<dem::OutputSpec> outputs(const Scene&) const override {
    return {{"sigma_t_MPa", "MPa", "tensile strength 2 F_max / (pi D t)", true, dem::kNonNegative},
            {"peak_approach_over_D", "1", "platen approach at the peak force over the diameter", true,
             dem::kNonNegative},
            {"cracks_tension", "1", "bonds broken in tension", true, dem::kNonNegative},
            {"cracks_shear", "1", "bonds broken in shear", true, dem::kNonNegative}};
  }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_brazilian_3d(scene, parameters, options);
  }
};

}  // namespace

void register_brazilian_test_3d(dem::LabTestRegistry& registry) {
  registry.add(std::make_unique<BrazilianTest3D>());
}

}  // namespace demcal::dem3d
