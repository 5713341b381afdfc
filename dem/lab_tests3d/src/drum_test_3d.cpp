// The rotating drum (He et al. 2019's verification test): a horizontal
// cylinder, its axis along y, part filled with a powder that first settles,
// then turns at a set speed; once the flow is steady, the free surface's
// angle in the drum's cross-section is sampled at a set interval and its
// mean is the dynamic angle of repose (the 2D heap's output name, aor_deg),
// their SD its scatter. The end walls turn with the drum.
//
//   "particles": as heap_3d,
//   "drum":      {"inner_diameter_m", "length_m", "fill_fraction" (the bed's share of the drum's volume,
//                 default 0.3), "bed_solids_fraction" (the settled bed's, default 0.55), "speed_rpm"},
//   "run":       {"settle_time_s", "measure_from_s" (after the drum starts), "measure_time_s", "sample_every_s",
//                 "surface_fraction", "steady_tolerance_deg", "bin_width_diameters", "max_wall_s",
//                 "local_damping", "safety_factor", "rayleigh_fraction"}
//
// Contact roles: "particle-particle" and "particle-wall" (the drum's shell and its two ends).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/line_fit.hpp"
#include "demcal/dem/run_watch.hpp"
#include "demcal/dem3d/drum_surface.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/powder_3d.hpp"
#include "demcal/dem3d/sphere_scene.hpp"
#include "powder_run.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::uint8_t kWallGroup = kPowderWallGroup;

struct DrumSpec {
  PowderSpec3d powder;
  double inner_diameter_m = 0, length_m = 0, fill_fraction = 0.3, bed_solids_fraction = 0.55, speed_rpm = 0;
  double settle_time_s = 0.5, measure_from_s = 1.0, measure_time_s = 2.0, sample_every_s = 0.05;
  double surface_fraction = 0.6, steady_tolerance_deg = 2.0, bin_width_diameters = 1.5, max_wall_s = 600;
  PowderStepping stepping;

  double radius_m() const { return 0.5 * inner_diameter_m; }
  double spin_rad_s() const { return speed_rpm * 2 * M_PI / 60; }
  // Centripetal over gravitational acceleration at the shell: the powder centrifuges at 1.
  double froude() const { return spin_rad_s() * spin_rad_s() * radius_m() / kPowderGravity_m_s2; }

  static DrumSpec from_scene(const Scene& scene, const std::map<std::string, double>& parameters);
};

DrumSpec DrumSpec::from_scene(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  DrumSpec s;
  s.powder = read_powder_section(scene, parameters);
  const nlohmann::json& d = scene.section("drum");
  require_known_fields(d, {"inner_diameter_m", "length_m", "fill_fraction", "bed_solids_fraction", "speed_rpm", "note"},
                       origin + ": drum");
  auto number = [&](const std::string& section, const nlohmann::json& object, const char* key, double& target,
                    bool required) { dem::read_section_number(scene, parameters, section, object, key, target, required); };
  number("drum", d, "inner_diameter_m", s.inner_diameter_m, true);
  number("drum", d, "length_m", s.length_m, true);
  number("drum", d, "fill_fraction", s.fill_fraction, false);
  number("drum", d, "bed_solids_fraction", s.bed_solids_fraction, false);
  number("drum", d, "speed_rpm", s.speed_rpm, true);
  const nlohmann::json& r = scene.section("run");
  std::vector<std::string> run_keys = {"settle_time_s", "measure_from_s", "measure_time_s", "sample_every_s",
                                       "surface_fraction", "steady_tolerance_deg", "bin_width_diameters",
                                       "max_wall_s", "note"};
  run_keys.insert(run_keys.end(), PowderStepping::keys().begin(), PowderStepping::keys().end());
  require_known_fields(r, run_keys, origin + ": run");
  for (const auto& [key, target] : std::vector<std::pair<const char*, double*>>{
           {"settle_time_s", &s.settle_time_s}, {"measure_from_s", &s.measure_from_s},
           {"measure_time_s", &s.measure_time_s}, {"sample_every_s", &s.sample_every_s},
           {"surface_fraction", &s.surface_fraction}, {"steady_tolerance_deg", &s.steady_tolerance_deg},
           {"bin_width_diameters", &s.bin_width_diameters}, {"max_wall_s", &s.max_wall_s}})
    number("run", r, key, *target, false);
  s.stepping.read(scene, parameters, r);

  const std::string dw = origin + ": drum";
  if (!(s.fill_fraction > 0 && s.fill_fraction <= 0.6)) throw Error(dw + ".fill_fraction must lie in (0, 0.6]");
  if (!(s.bed_solids_fraction > 0 && s.bed_solids_fraction <= 0.74))
    throw Error(dw + ".bed_solids_fraction must lie in (0, 0.74]");
  // The whole fill is placed at once, loose, over the drum: the bed's particles at this share of its volume.
  s.powder.solids_fraction = s.fill_fraction * s.bed_solids_fraction;
  s.powder.validate(origin + ": particles (with drum.fill_fraction x drum.bed_solids_fraction as the loose fill's)");
  const double length = s.powder.longest_m();
  if (!(s.inner_diameter_m >= 8 * length))
    throw Error(dw + ".inner_diameter_m " + format_double(s.inner_diameter_m) + " m is less than 8 particle lengths (" +
                format_double(8 * length) + " m): no free surface to fit");
  if (!(s.length_m >= 2 * length)) throw Error(dw + ".length_m must be at least two particle lengths");
  if (!(s.speed_rpm > 0)) throw Error(dw + ".speed_rpm must be positive");
  if (!(s.froude() < 1))
    throw Error(dw + ".speed_rpm " + format_double(s.speed_rpm) + " centrifuges the powder: the Froude number " +
                "omega^2 R / g is " + format_double(s.froude()) + " (it must be below 1)");
  const std::string rw = origin + ": run";
  if (!(s.settle_time_s >= 0)) throw Error(rw + ".settle_time_s must be >= 0");
  if (!(s.measure_from_s >= 0)) throw Error(rw + ".measure_from_s must be >= 0");
  if (!(s.measure_time_s > 0)) throw Error(rw + ".measure_time_s must be positive");
  if (!(s.sample_every_s > 0 && s.sample_every_s <= 0.25 * s.measure_time_s))
    throw Error(rw + ".sample_every_s must lie in (0, measure_time_s / 4] (at least four samples)");
  if (!(s.surface_fraction > 0 && s.surface_fraction <= 1)) throw Error(rw + ".surface_fraction must lie in (0, 1]");
  if (!(s.steady_tolerance_deg > 0)) throw Error(rw + ".steady_tolerance_deg must be positive");
  if (!(s.bin_width_diameters > 0)) throw Error(rw + ".bin_width_diameters must be positive");
  if (!(s.max_wall_s > 0)) throw Error(rw + ".max_wall_s must be positive");
  return s;
}

}  // namespace

double drum_surface_angle_deg(const std::vector<double>& x_m, const std::vector<double>& z_m,
                              const std::vector<double>& radius_m, double r, double bin_m, double surface_fraction) {
  const auto bins = static_cast<std::size_t>(std::ceil(2 * r / bin_m));
  std::vector<double> top(bins, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const auto b = static_cast<std::size_t>(std::clamp((x_m[i] + r) / bin_m, 0.0, static_cast<double>(bins - 1)));
    top[b] = std::max(top[b], z_m[i] + radius_m[i]);
  }
  std::size_t first = bins, last = 0;
  for (std::size_t b = 0; b < bins; ++b)
    if (std::isfinite(top[b])) {
      first = std::min(first, b);
      last = b;
    }
  if (first > last) throw Error("no particle in the drum's cross-section");
  const double span = static_cast<double>(last - first + 1), skip = 0.5 * (1 - surface_fraction) * span;
  std::vector<double> x, z;
  for (std::size_t b = first; b <= last; ++b) {
    const double k = static_cast<double>(b - first);
    if (k < skip || k > span - 1 - skip || !std::isfinite(top[b])) continue;
    x.push_back(-r + (static_cast<double>(b) + 0.5) * bin_m);
    z.push_back(top[b]);
  }
  const dem::FittedLine line =
      dem::fit_line(x, z, "too few surface bins to fit the drum's free surface (widen the drum or narrow the bins)",
                    "the drum's free surface has no horizontal spread");
  return std::atan(std::abs(line.slope)) * 180.0 / M_PI;
}

namespace {

double surface_angle_deg(const World& world, const DrumSpec& s, double bin_m) {
  const Spheres& sp = world.spheres;
  return drum_surface_angle_deg(sp.x, sp.z, sp.radius, s.radius_m(), bin_m, s.surface_fraction);
}

std::string escaped(const World& world, const DrumSpec& s) {
  const double margin = 2 * s.powder.radius_max_m, reach = s.radius_m() + margin, half = 0.5 * s.length_m + margin;
  const Spheres& sp = world.spheres;
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const Vec3 x = sp.position(i), v = sp.velocity(i);
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z))
      return "a particle's position or velocity is not finite at t = " + format_double(world.time_s()) + " s";
    if (std::hypot(x.x, x.z) > reach || std::abs(x.y) > half)
      return "a particle left the drum at t = " + format_double(world.time_s()) +
             " s: the time step is too large for the contacts";
  }
  return "";
}

dem::TestResult run_drum_3d(const Scene& scene, const std::map<std::string, double>& parameters,
                            const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const DrumSpec s = DrumSpec::from_scene(scene, parameters);
  World world(powder_settings(scene, parameters, s.powder, s.stepping, options));
  bind_contact_models(world, scene, parameters);
  const double r = s.radius_m(), half = 0.5 * s.length_m;
  world.walls.push_back(make_cylinder({0, -half, 0}, {0, 1, 0}, r, s.length_m, true, kWallGroup));
  world.walls.push_back(make_plane({0, -half, 0}, {0, 1, 0}, kWallGroup));
  world.walls.push_back(make_plane({0, half, 0}, {0, -1, 0}, kWallGroup));

  // The loose fill over the whole drum, placed in a frustum about z of the
  // drum's size, then turned a quarter about x so that its axis lies along y.
  const Frustum drum_volume{-half, half, r, r};
  std::vector<PowderParticle3d> particles =
      place_powder_3d(s.powder, drum_volume, options.seed, scene.origin() + ": drum (the fill)");
  const Quaternion quarter = rotation_by({0.5 * M_PI, 0, 0});
  for (PowderParticle3d& p : particles) {
    p.centre_m = to_world(quarter, p.centre_m);
    p.orientation = normalised(quarter * p.orientation);
  }
  add_powder_3d(world, particles, s.powder, kPowderGroup, options.particle_order_seed);
  world.refresh();

  dem::TestResult result;
  result.particles = world.spheres.size();
  result.specimen_info["particles"] = static_cast<double>(particles.size());
  result.specimen_info["clumps"] = static_cast<double>(world.clumps().size());
  result.specimen_info["froude"] = s.froude();
  const double end_s = s.settle_time_s + s.measure_from_s + s.measure_time_s;
  dem::RunWatch watch("drum", s.max_wall_s, start, end_s, "drum_3d (% of the run's time)", options.progress);
  const auto loading_start = std::chrono::steady_clock::now();
  const double bin_m = s.bin_width_diameters * (s.powder.radius_min_m + s.powder.radius_max_m);
  std::vector<double> angles;
  bool turning = false;
  result.ok = true;
  auto fail = [&](const std::string& why) {
    result.ok = false;
    result.reason = why;
  };
  double next_sample = s.settle_time_s + s.measure_from_s;
  for (;;) {
    const double t = world.time_s();
    if (!turning && t >= s.settle_time_s) {
      for (Wall& w : world.walls) w.spin_rad_s = {0, s.spin_rad_s(), 0};  // shell and ends turn together
      turning = true;
    }
    const double until = std::min(turning ? next_sample : s.settle_time_s, end_s);
    const auto steps = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil((until - t) / world.dt_s())));
    world.run(steps);
    const std::string bad = escaped(world, s);
    if (!bad.empty()) {
      fail(bad);
      break;
    }
    if (!watch.carry_on(world.time_s())) {
      fail(watch.timeout_reason());
      break;
    }
    if (turning && world.time_s() >= next_sample - 1e-12) {
      try {
        angles.push_back(surface_angle_deg(world, s, bin_m));
      } catch (const Error& e) {
        fail(e.what());
        break;
      }
      next_sample += s.sample_every_s;
    }
    if (world.time_s() >= end_s - 1e-12) break;
  }
  watch.finish();
  finish_powder_run(world, scene, parameters, s.powder, options, start, loading_start, result);
  // The samples as the result's curve (time in axial_strain's column), also when the run fails: they show
  // how far from steady it was.
  for (std::size_t k = 0; k < angles.size(); ++k) {
    dem::CurvePoint point;
    point.axial_strain = s.settle_time_s + s.measure_from_s + static_cast<double>(k) * s.sample_every_s;
    point.lateral_strain = angles[k];
    result.curve.push_back(point);
  }
  if (!result.ok) return result;
  // Steady when the two halves of the samples agree within the tolerance.
  const std::size_t n = angles.size(), half_n = n / 2;
  auto mean_of = [&](std::size_t a, std::size_t b) {
    double sum = 0;
    for (std::size_t k = a; k < b; ++k) sum += angles[k];
    return sum / static_cast<double>(b - a);
  };
  if (n < 4) {
    fail("only " + std::to_string(n) + " surface samples (at least 4): lengthen run.measure_time_s");
    return result;
  }
  const double first = mean_of(0, half_n), second = mean_of(half_n, n), mean = mean_of(0, n);
  double sum2 = 0;
  for (double a : angles) sum2 += (a - mean) * (a - mean);
  result.specimen_info["aor_first_half_deg"] = first;
  result.specimen_info["aor_second_half_deg"] = second;
  result.specimen_info["samples"] = static_cast<double>(n);
  if (std::abs(first - second) > s.steady_tolerance_deg) {
    // What two halves of independent samples of this scatter would differ
    // by (1 SD): a tolerance near it fails steady runs by chance.
    const double sd = std::sqrt(sum2 / static_cast<double>(n - 1));
    const double chance = sd * std::sqrt(1.0 / static_cast<double>(half_n) + 1.0 / static_cast<double>(n - half_n));
    fail("no steady state: the surface's angle moved from " + format_double(first) + " to " + format_double(second) +
         " deg between the halves of the measuring window (run.steady_tolerance_deg " +
         format_double(s.steady_tolerance_deg) + "); start measuring later (run.measure_from_s). The samples scatter " +
         "by " + format_double(sd) + " deg (SD), so the halves of a steady flow differ by about " +
         format_double(chance) + " deg or more: a tolerance below 2.5 times that, or a short window, fails steady " +
         "runs by chance");
    return result;
  }
  result.macro["aor_deg"] = mean;
  result.macro["aor_sd_deg"] = std::sqrt(sum2 / static_cast<double>(n - 1));
  return result;
}

class DrumTest3d : public PowderTest3d {
 public:
  std::string name() const override { return "drum_3d"; }
  std::string description() const override {
    return "rotating drum in 3D: a part-filled horizontal cylinder turns; the free surface's dynamic angle of repose";
  }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-wall", kWallGroup, "particles against the drum's shell and its two ends"}};
  }
  std::vector<dem::SceneSection> sections() const override {
    return {particles_section(),
            {"drum", "the drum's size, fill and speed", false},
            {"run", "settling, the measuring window and its samples, the time step", false}};
  }
  void check_scene(const Scene& scene) const override { DrumSpec::from_scene(scene, scene.resolve({})); }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"aor_deg"}; }
  std::vector<dem::OutputSpec> outputs(const Scene&) const override {
    return {{"aor_deg", "deg", "dynamic angle of repose: the mean over the measuring window of the free surface's "
                               "angle in the drum's cross-section", true, dem::kAcuteAngleDeg},
            {"aor_sd_deg", "deg", "the SD of the sampled angles", true, dem::kNonNegative}};
  }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_drum_3d(scene, parameters, options);
  }
};

}  // namespace

void register_drum_test_3d(dem::LabTestRegistry& registry) { registry.add(std::make_unique<DrumTest3d>()); }

}  // namespace demcal::dem3d
