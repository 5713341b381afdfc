#include "demcal/dem/biaxial_test.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/wall_timeout.hpp"
#include "demcal/dem/equilibrium.hpp"
#include "demcal/dem/builtin_tests.hpp"
#include "demcal/dem/confined_series.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/ucs_test.hpp"

namespace demcal::dem {
namespace {

enum WallIndex : std::size_t { kBottom = 0, kTop = 1, kLeft = 2, kRight = 3 };

double width_m(const World& w) { return w.walls[kRight].x0 - w.walls[kLeft].x0; }
double height_m(const World& w) { return w.walls[kTop].y0 - w.walls[kBottom].y0; }

// Compressive stress the disks exert on wall `w` over `length_m`.
double wall_stress_pa(const World& world, std::size_t w, double length_m) {
  const Wall& wall = world.walls[w];
  return -(wall.fx * wall.inward_nx + wall.fy * wall.inward_ny) / (length_m * world.settings().thickness_m);
}

// Puts wall `w` under a stress servo whose gain closes kServoRelaxation of the
// error per step against the stiffness of the disks touching it now; a wall
// without contacts moves at its top speed.
void servo(World& world, std::size_t w, double target_pa, double length_m, double max_speed_m_s) {
  Wall& wall = world.walls[w];
  wall.servo = true;
  wall.servo_target_stress_pa = target_pa;
  wall.servo_length_m = length_m;
  wall.servo_max_speed_m_s = max_speed_m_s;
  const double k = world.wall_contact_stiffness_n_m(w);
  wall.servo_gain_m_s_per_pa = k > 0 ? kServoRelaxation * length_m * world.settings().thickness_m / (k * world.dt_s())
                                     : max_speed_m_s / target_pa;
}

// All four walls servoed to the confining stress until each holds it within
// 0.5 % and the specimen is at rest; the reason when it does not get there
// (too many steps, loading.max_wall_s since `start`, or an instability).
std::string consolidate(World& world, double sigma_3_pa, double max_speed_m_s, std::uint64_t max_steps,
                        const LoadingSpec& loading, std::chrono::steady_clock::time_point start) {
  constexpr int kBlock = 50;
  for (std::uint64_t done = 0; done < max_steps; done += kBlock) {
    const std::string unstable = instability(world, loading.platen_velocity_m_s);
    if (!unstable.empty()) return unstable + " while confining";
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > loading.max_wall_s)
      return wall_timeout_reason("after " + std::to_string(elapsed) + " s while confining (loading.max_wall_s)");
    const double W = width_m(world), H = height_m(world);
    servo(world, kBottom, sigma_3_pa, W, max_speed_m_s);
    servo(world, kTop, sigma_3_pa, W, max_speed_m_s);
    servo(world, kLeft, sigma_3_pa, H, max_speed_m_s);
    servo(world, kRight, sigma_3_pa, H, max_speed_m_s);
    world.run(kBlock);
    bool held = true;
    for (std::size_t w = 0; w < 4; ++w)
      held = held && std::abs(wall_stress_pa(world, w, w < 2 ? width_m(world) : height_m(world)) - sigma_3_pa) <=
                         0.005 * sigma_3_pa;
    if (held && force_ratio(world) < 1e-3) return "";
  }
  return "the confinement to " + format_double(sigma_3_pa / 1e6) + " MPa did not settle within " +
         std::to_string(max_steps) + " steps";
}

}  // namespace

TestResult confine_and_load(World& world, double confining_stress_pa, const LoadingSpec& loading,
                            const RunOptions& options, std::chrono::steady_clock::time_point start) {
  if (world.walls.size() != 4) throw Error("the biaxial test needs four walls (bottom, top, left, right)");
  const double v = loading.platen_velocity_m_s, t = world.settings().thickness_m;
  const double max_speed = kServoSpeedOverPlatenSpeed * v;
  TestResult result;
  world.refresh();
  result.reason = consolidate(world, confining_stress_pa, max_speed, 2000000, loading, start);
  if (!result.reason.empty()) return result;
  // The loading starts here: bonds broken while confining are reported on
  // their own, not as cracks of the test (nor as its post-peak sign).
  result.macro["cracks_confining"] = static_cast<double>(world.breaks().size());
  const std::uint64_t confining_steps = world.steps_done();
  world.start_test();

  // Loading: the platens at the loading velocity, the side walls still servoed.
  const double H0 = height_m(world), W0 = width_m(world);
  for (std::size_t w : {kBottom, kTop}) world.walls[w].servo = false;
  world.walls[kBottom].vx = world.walls[kTop].vx = 0;
  world.walls[kBottom].vy = v;
  world.walls[kTop].vy = -v;
  LoadingMonitor monitor(loading, options, start, W0 * H0 * t);
  double next_record = 0;
  for (std::uint64_t s = 0;; ++s) {
    if (s % 50 == 0) {
      // The side walls' gain follows their contacts, their stress the current height.
      servo(world, kLeft, confining_stress_pa, height_m(world), max_speed);
      servo(world, kRight, confining_stress_pa, height_m(world), max_speed);
    }
    world.step();
    const double H = height_m(world), W = width_m(world);
    const double strain = (H0 - H) / H0;
    if (strain < next_record) continue;
    next_record = strain + loading.record_strain;
    CurvePoint point;
    point.axial_strain = strain;
    const double sigma_1 = platen_force(world) / (W * t);
    point.confining_stress_pa = 0.5 * (wall_stress_pa(world, kLeft, H) + wall_stress_pa(world, kRight, H));
    point.stress_pa = sigma_1 - point.confining_stress_pa;
    point.lateral_strain = (W - W0) / W0;
    point.cracks = world.breaks().size();
    if (!monitor.record(DiskMonitoredWorld(world), point, result, "axial strain " + std::to_string(strain))) break;
  }
  result.steps = confining_steps;  // added to the loading's steps by record_run_end's caller
  if (!result.ok) return result;
  add_confined_values(result);
  return result;
}

TestResult run_biaxial(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double>& confinements = scene.loading().confining_stresses_pa;
  if (confinements.empty()) throw Error(scene.origin() + ": loading.confining_stresses_MPa: missing");
  Specimen specimen = cached_specimen(specimen_spec(scene, parameters, options.seed), options.cache_dir);
  TestResult series;
  series.particles = specimen.size();
  series.porosity = specimen.porosity;
  std::vector<double> sigma_3, sigma_1;
  std::chrono::steady_clock::duration loading_time{};
  for (std::size_t k = 0; k < confinements.size(); ++k) {
    const std::string n = std::to_string(k + 1);
    std::map<std::string, double> info;
    World world = make_platen_world(scene, parameters, specimen, options.seed, nullptr, &info, true, nullptr, &options);
    if (k == 0) series.specimen_info = info;
    RunOptions own = options;  // each specimen's snapshots in a folder of its own
    if (!options.vtk_dir.empty()) {
      ::mkdir(options.vtk_dir.c_str(), 0755);
      own.vtk_dir = options.vtk_dir + "/confinement_" + n;
    }
    // loading.max_wall_s holds for each specimen of the series.
    const auto loading_start = std::chrono::steady_clock::now();
    TestResult one = confine_and_load(world, confinements[k], scene.loading(), own, loading_start);
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
    add_confinement_outputs(one, n, series);
    series.ended_by += (series.ended_by.empty() ? "" : "; ") + n + ": " + one.ended_by;
    sigma_3.push_back(one.macro.at("sigma_3_peak_MPa") * 1e6);
    sigma_1.push_back(one.macro.at("sigma_1_peak_MPa") * 1e6);
  }
  series.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  series.test_wall_s = std::chrono::duration<double>(loading_time).count();
  if (!series.reason.empty()) return series;
  if (confinements.size() >= 2 && !add_envelopes(sigma_3, sigma_1, series)) return series;
  series.ok = true;
  return series;
}

namespace {

class BiaxialTest : public PackedTest {
 public:
  std::string name() const override { return "biaxial"; }
  // 1: a series also reports the Hoek-Brown hb_ outputs (2026-12-03).
  // 2: E's and nu's window a tenth of the points to the peak (ucs_macro_values).
  int results_version() const override { return 2; }
  // Its confining stresses are numbers in `loading`, not stress-like
  // parameters: scaling the parameters alone does not scale its outputs
  // (the law does, with the confinements scaled too: the invariant driver
  // checks that). So no calibration may rest on it.
  bool exact_scaling() const override { return false; }
  std::string description() const override {
    return "biaxial (2D triaxial) compression: servo side walls hold each of loading.confining_stresses_MPa while "
           "frictionless platens approach; a series fits the Mohr-Coulomb and Hoek-Brown envelopes";
  }
  std::vector<BoundaryRole> boundary_roles() const override {
    return {{"particle-platen", kPlatenGroup, "the specimen's disks against the platens and the confining side walls"}};
  }
  // A series: its envelope's parameters (one confinement: its peak).
  bool confined() const override { return true; }
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
  std::vector<OutputSpec> outputs(const Scene& scene) const override {
    return confined_series_outputs(scene.loading().confining_stresses_pa, "the side walls", "side walls",
                                   kPoissonRatio2D);
  }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_biaxial(scene, parameters, options);
  }
};

}  // namespace

void register_biaxial_test(LabTestRegistry& registry) { registry.add(std::make_unique<BiaxialTest>()); }

}  // namespace demcal::dem
