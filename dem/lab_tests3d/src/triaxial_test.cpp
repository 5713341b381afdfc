// The triaxial test of a sphere cylinder (PFC3D's): the specimen between two
// frictionless platens inside a frictionless cylindrical wall is brought to an
// isotropic stress sigma_3 by stress servos on all three walls, then the
// platens approach at the loading velocity while the cylinder's radius keeps
// sigma_3 on the lateral surface. One specimen (the same packing) per
// confining stress; the series fits the Mohr-Coulomb and Hoek-Brown envelopes.
// The outputs are the 2D biaxial series' (numbered per confinement), so a
// study's targets carry over.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/wall_timeout.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem/confined_series.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/material_pressure.hpp"
#include "demcal/dem3d/sphere_scene.hpp"

namespace demcal::dem3d {
namespace {

enum WallIndex : std::size_t { kBottom = 0, kTop = 1, kSide = 2 };

// The servos' top speed over the platen speed: fast enough to follow the
// specimen's dilation, slow enough not to ring it.
constexpr double kServoSpeedOverPlatenSpeed = 10.0;

double height_m(const World& w) { return w.walls[kTop].point_m.z - w.walls[kBottom].point_m.z; }
double radius_m(const World& w) { return w.walls[kSide].radius_m; }
double platen_stress_pa(const World& w) {
  const double r = radius_m(w);
  return 0.5 * (w.walls[kBottom].normal_force_n + w.walls[kTop].normal_force_n) / (M_PI * r * r);
}
double side_stress_pa(const World& w) { return w.walls[kSide].normal_force_n / (2 * M_PI * radius_m(w) * height_m(w)); }

// The loaded areas the servos divide by, at the present size.
void set_servo_areas(World& w) {
  const double r = radius_m(w);
  w.walls[kBottom].servo_area_m2 = w.walls[kTop].servo_area_m2 = M_PI * r * r;
  w.walls[kSide].servo_area_m2 = 2 * M_PI * r * height_m(w);
}

// The specimen in its vessel (platens at the end faces, the cylinder at its
// wall, each touching the spheres that touched it with no force), bonded.
// `reason` says why bonding failed (a pressured specimen that did not settle).
World make_world(const Scene& scene, const std::map<std::string, double>& parameters, const SphereSpecimen& specimen,
                 const dem::RunOptions& options, std::map<std::string, double>& info, std::string& reason) {
  World world = specimen_world(scene, parameters, specimen, options);
  world.walls = {make_plane({0, 0, 0}, {0, 0, 1}, kPlatenGroup),
                 make_plane({0, 0, specimen.height_m}, {0, 0, -1}, kPlatenGroup),
                 make_cylinder({0, 0, 0}, {0, 0, 1}, 0.5 * specimen.width_m, 0.0, true, kPlatenGroup)};
  reason = bond_specimen(world, scene, specimen, options.seed, info);
  return world;
}

// All three walls servoed to sigma_3 until each holds it within 0.5 % and the
// specimen is at rest; the reason when it does not get there.
std::string consolidate(World& world, double sigma_3_pa, double max_speed_m_s, std::uint64_t max_steps,
                        const dem::LoadingSpec& loading, std::chrono::steady_clock::time_point start) {
  constexpr int kBlock = 50;
  for (Wall& w : world.walls) {
    w.servo = true;
    w.servo_target_stress_pa = sigma_3_pa;
    w.servo_max_speed_m_s = max_speed_m_s;
  }
  for (std::uint64_t done = 0; done < max_steps; done += kBlock) {
    const std::string unstable = SphereMonitoredWorld(world).instability(loading.platen_velocity_m_s);
    if (!unstable.empty()) return unstable + " while confining";
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > loading.max_wall_s)
      return wall_timeout_reason("after " + std::to_string(elapsed) + " s while confining (loading.max_wall_s)");
    set_servo_areas(world);
    world.run(kBlock);
    const bool held = std::abs(platen_stress_pa(world) - sigma_3_pa) <= 0.005 * sigma_3_pa &&
                      std::abs(side_stress_pa(world) - sigma_3_pa) <= 0.005 * sigma_3_pa;
    if (held && world.force_ratio() < 1e-3) return "";
  }
  return "the confinement to " + format_double(sigma_3_pa / 1e6) + " MPa did not settle within " +
         std::to_string(max_steps) + " steps";
}

dem::TestResult confine_and_load(World& world, double sigma_3_pa, const dem::LoadingSpec& loading,
                                 const dem::RunOptions& options, std::chrono::steady_clock::time_point start) {
  const double v = loading.platen_velocity_m_s, max_speed = kServoSpeedOverPlatenSpeed * v;
  dem::TestResult result;
  result.reason = consolidate(world, sigma_3_pa, max_speed, 2000000, loading, start);
  if (!result.reason.empty()) return result;
  result.macro["cracks_confining"] = static_cast<double>(world.breaks().size());
  const std::uint64_t confining_steps = world.steps_done();
  world.start_test();

  const double H0 = height_m(world), R0 = radius_m(world);
  for (std::size_t w : {kBottom, kTop}) world.walls[w].servo = false;
  world.walls[kBottom].velocity_m_s = {0, 0, v};
  world.walls[kTop].velocity_m_s = {0, 0, -v};
  dem::LoadingMonitor monitor(loading, options, start, M_PI * R0 * R0 * H0);
  double next_record = 0;
  for (std::uint64_t s = 0;; ++s) {
    if (s % 50 == 0) set_servo_areas(world);  // the side's stress over its present area
    world.step();
    const double strain = (H0 - height_m(world)) / H0;
    if (strain < next_record) continue;
    next_record = strain + loading.record_strain;
    dem::CurvePoint point;
    point.axial_strain = strain;
    point.confining_stress_pa = side_stress_pa(world);
    point.stress_pa = platen_stress_pa(world) - point.confining_stress_pa;
    point.lateral_strain = (radius_m(world) - R0) / R0;
    point.cracks = world.breaks().size();
    if (!monitor.record(SphereMonitoredWorld(world), point, result, "axial strain " + std::to_string(strain))) break;
  }
  result.steps = confining_steps;
  if (!result.ok) return result;
  dem::add_confined_values(result);
  return result;
}

dem::TestResult run_triaxial(const Scene& scene, const std::map<std::string, double>& parameters,
                             const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double>& confinements = scene.loading().confining_stresses_pa;
  if (confinements.empty()) throw Error(scene.origin() + ": loading.confining_stresses_MPa: missing");
  dem::TestResult series;
  SphereSpecimen specimen;
  if (!test_specimen(scene, parameters, options, series, specimen)) return series;
  const std::map<std::string, double> pressure_info = series.specimen_info;
  series.particles = specimen.size();
  series.porosity = specimen.porosity;
  std::vector<double> sigma_3, sigma_1;
  std::chrono::steady_clock::duration loading_time{};
  for (std::size_t k = 0; k < confinements.size(); ++k) {
    const std::string n = std::to_string(k + 1);
    std::map<std::string, double> info = pressure_info;
    std::string failed;
    World world = make_world(scene, parameters, specimen, options, info, failed);
    if (k == 0) series.specimen_info = info;
    if (!failed.empty()) {
      series.reason = "confinement " + n + ": " + failed;
      break;
    }
    dem::RunOptions own = options;  // each specimen's snapshots in a folder of its own
    if (!options.vtk_dir.empty()) {
      ::mkdir(options.vtk_dir.c_str(), 0755);
      own.vtk_dir = options.vtk_dir + "/confinement_" + n;
    }
    const auto loading_start = std::chrono::steady_clock::now();
    dem::TestResult one = confine_and_load(world, confinements[k], scene.loading(), own, loading_start);
    const std::uint64_t confining_steps = one.steps;
    record_run_end(world, own, loading_start, loading_start, one);
    one.steps += confining_steps;
    loading_time += std::chrono::steady_clock::now() - loading_start;
    series.steps += one.steps;
    series.dt_s = one.dt_s;
    series.threads = one.threads;
    series.density_scaling_dt_s = one.density_scaling_dt_s;
    series.curve.insert(series.curve.end(), one.curve.begin(), one.curve.end());
    if (!one.ok) {
      series.reason = "confinement " + n + " (" + format_double(confinements[k] / 1e6) + " MPa): " + one.reason;
      break;
    }
    dem::add_confinement_outputs(one, n, series);
    series.ended_by += (series.ended_by.empty() ? "" : "; ") + n + ": " + one.ended_by;
    sigma_3.push_back(one.macro.at("sigma_3_peak_MPa") * 1e6);
    sigma_1.push_back(one.macro.at("sigma_1_peak_MPa") * 1e6);
  }
  series.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  series.test_wall_s = std::chrono::duration<double>(loading_time).count();
  if (!series.reason.empty()) return series;
  if (confinements.size() >= 2 && !dem::add_envelopes(sigma_3, sigma_1, series)) return series;
  series.ok = true;
  return series;
}

class TriaxialTest : public PackedSphereTest {
 public:
  std::string name() const override { return "triaxial"; }
  std::string description() const override {
    return "triaxial compression of a sphere cylinder: a servo cylinder holds each of loading.confining_stresses_MPa "
           "while frictionless platens approach; a series fits the Mohr-Coulomb and Hoek-Brown envelopes";
  }
  // The confinements are numbers of `loading`, not parameters (as the biaxial series).
  bool exact_scaling() const override { return false; }
  bool confined() const override { return true; }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-platen", kPlatenGroup, "the specimen's spheres against the platens and the confining cylinder"}};
  }
  void check_scene(const Scene& scene) const override {
    PackedSphereTest::check_scene(scene);
    if (sphere_specimen_spec(scene, scene.resolve({}), 1).vessel != Vessel::cylinder)
      throw Error(scene.origin() + ": specimen.shape: triaxial confines a cylinder (\"shape\": \"cylinder\")");
    if (scene.loading().confining_stresses_pa.empty())
      throw Error(scene.origin() + ": loading.confining_stresses_MPa: missing (the triaxial series' sigma_3 values)");
  }
  std::vector<std::string> headline_outputs(const Scene& scene) const override {
    if (scene.loading().confining_stresses_pa.size() >= 2) return {"c_MPa", "phi_deg", "hb_m_i"};
    return {"q_peak_MPa_1"};
  }
  std::vector<std::string> modulus_outputs(const Scene& scene) const override {
    std::vector<std::string> names;
    for (std::size_t k = 1; k <= scene.loading().confining_stresses_pa.size(); ++k)
      names.push_back("E_GPa_" + std::to_string(k));
    return names;
  }
  std::pair<std::string, std::string> curve_axes() const override { return {"axial strain", "deviatoric stress (MPa)"}; }
  std::vector<dem::OutputSpec> outputs(const Scene& scene) const override {
    return dem::confined_series_outputs(scene.loading().confining_stresses_pa, "the cylinder",
                                        "the cylinder's radius", kPoissonRatio3D);
  }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_triaxial(scene, parameters, options);
  }
};

}  // namespace

void register_triaxial_test(dem::LabTestRegistry& registry) { registry.add(std::make_unique<TriaxialTest>()); }

}  // namespace demcal::dem3d
