// The baffle lift (He et al. 2019's static verification test): a box of
// powder loses one side wall, the baffle, lifted at a set speed; part of the
// powder runs out over the floor and what stays leans on the back wall. Once
// it has settled (kinetic energy below a set share of the potential), the
// slope's angle is fitted to the surface profile along the box in slices
// across it, away from the side walls. The outputs carry the heap's names.
//
//   "particles": as heap_3d,
//   "box":       {"length_m" (from the back wall to the baffle, along x), "width_m", "height_m",
//                 "fill_height_m" (the top of the loose fill, default 0.8 x height), "solids_fraction" (the loose
//                 fill's, default 0.25), "run_out_m" (the floor beyond the baffle, default 2 x length)},
//   "baffle":    {"lift_speed_m_s" (default 0.1), "lift_height_m" (default the box's height)},
//   "run":       {"fill_time_s" (before the lift), "settle_from_s" (after it), "max_time_s", "check_every_s",
//                 "settle_kinetic_ratio",
//                 "max_wall_s", "bin_width_diameters", "slices", "local_damping", "safety_factor",
//                 "rayleigh_fraction"}
//
// Contact roles: "particle-particle" and "particle-wall" (the box's walls, the baffle, the floor, the domain).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/angle_of_repose.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/run_watch.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/powder_3d.hpp"
#include "demcal/dem3d/sphere_scene.hpp"
#include "powder_run.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::uint8_t kWallGroup = kPowderWallGroup;
constexpr std::int32_t kBackMesh = 0, kLeftMesh = 1, kRightMesh = 2, kBaffleMesh = 3;

struct BaffleSpec {
  PowderSpec3d powder;
  double length_m = 0, width_m = 0, height_m = 0, fill_height_m = 0, run_out_m = 0;
  double lift_speed_m_s = 0.1, lift_height_m = 0;
  dem::SettleRun run = defaults();  // the run's time limits and settling criterion (run_watch.hpp)
  double settle_from_s = 0.25;
  double bin_width_diameters = 1.5, slices = 3;
  PowderStepping stepping;

  double lift_ends_at_s() const { return run.fill_time_s + lift_height_m / lift_speed_m_s; }
  // Settling is judged from here on: the powder at rest before it has started to run out is not settled.
  double settle_check_from_s() const { return lift_ends_at_s() + settle_from_s; }
  double domain_radius_m() const { return std::hypot(0.5 * length_m + run_out_m, 0.5 * width_m); }
  // The loose fill: the box's inside up to fill_height_m.
  UprightBox fill_region() const { return {0.5 * length_m, 0.5 * width_m, 0.0, fill_height_m}; }
  // The band across the box the slope is measured in: clear of the side walls by a particle length.
  double measured_half_width_m() const { return 0.5 * width_m - powder.longest_m(); }

  static BaffleSpec from_scene(const Scene& scene, const std::map<std::string, double>& parameters);

 private:
  static dem::SettleRun defaults() {
    dem::SettleRun run;
    run.fill_time_s = 0.5;
    run.max_time_s = 4;
    run.check_every_s = 0.01;
    return run;
  }
};

BaffleSpec BaffleSpec::from_scene(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  BaffleSpec s;
  auto number = [&](const std::string& section, const nlohmann::json& object, const char* key, double& target,
                    bool required) { dem::read_section_number(scene, parameters, section, object, key, target, required); };
  s.powder = read_powder_section(scene, parameters);

  const nlohmann::json& b = scene.section("box");
  require_known_fields(b, {"length_m", "width_m", "height_m", "fill_height_m", "solids_fraction", "run_out_m", "note"},
                       origin + ": box");
  number("box", b, "length_m", s.length_m, true);
  number("box", b, "width_m", s.width_m, true);
  number("box", b, "height_m", s.height_m, true);
  s.fill_height_m = 0.8 * s.height_m;
  number("box", b, "fill_height_m", s.fill_height_m, false);
  number("box", b, "solids_fraction", s.powder.solids_fraction, false);
  s.run_out_m = 2 * s.length_m;
  number("box", b, "run_out_m", s.run_out_m, false);

  const nlohmann::json& l = scene.section("baffle");
  require_known_fields(l, {"lift_speed_m_s", "lift_height_m", "note"}, origin + ": baffle");
  number("baffle", l, "lift_speed_m_s", s.lift_speed_m_s, false);
  s.lift_height_m = s.height_m;
  number("baffle", l, "lift_height_m", s.lift_height_m, false);

  const nlohmann::json& r = scene.section("run");
  std::vector<std::string> run_keys = dem::SettleRun::keys();
  run_keys.insert(run_keys.end(), PowderStepping::keys().begin(), PowderStepping::keys().end());
  run_keys.insert(run_keys.end(), {"settle_from_s", "bin_width_diameters", "slices", "note"});
  require_known_fields(r, run_keys, origin + ": run");
  s.run.read(scene, parameters, r);
  number("run", r, "settle_from_s", s.settle_from_s, false);
  number("run", r, "bin_width_diameters", s.bin_width_diameters, false);
  number("run", r, "slices", s.slices, false);
  s.stepping.read(scene, parameters, r);

  s.powder.validate(origin + ": particles");
  const std::string bw = origin + ": box";
  const double length = s.powder.longest_m();
  // A slope needs room for several bins along the box, and the measured band room for a slice across it.
  if (!(s.length_m >= 8 * length))
    throw Error(bw + ".length_m " + format_double(s.length_m) + " m is less than 8 particle lengths (" +
                format_double(8 * length) + " m): too short for a slope to fit");
  if (!(s.width_m >= 6 * length))
    throw Error(bw + ".width_m " + format_double(s.width_m) + " m is less than 6 particle lengths (" +
                format_double(6 * length) + " m): no band away from the side walls to measure in");
  if (!(s.height_m > 0)) throw Error(bw + ".height_m must be positive");
  if (!(s.fill_height_m >= 2 * length && s.fill_height_m <= s.height_m))
    throw Error(bw + ".fill_height_m must lie in [2 particle lengths, height_m]");
  if (!(s.run_out_m >= 2 * length)) throw Error(bw + ".run_out_m must be at least two particle lengths");
  const std::string lw = origin + ": baffle";
  if (!(s.lift_speed_m_s > 0)) throw Error(lw + ".lift_speed_m_s must be positive");
  if (!(s.lift_height_m >= s.fill_height_m))
    throw Error(lw + ".lift_height_m must be at least box.fill_height_m (the powder must be able to run out)");
  const std::string rw = origin + ": run";
  s.run.validate(rw);
  if (!(s.settle_from_s >= 0)) throw Error(rw + ".settle_from_s must be >= 0");
  if (!(s.run.max_time_s > s.settle_check_from_s()))
    throw Error(rw + ".max_time_s " + format_double(s.run.max_time_s) + " s ends before settling is checked (from " +
                format_double(s.settle_check_from_s()) +
                " s: fill_time_s + baffle.lift_height_m / lift_speed_m_s + settle_from_s)");
  if (!(s.bin_width_diameters > 0)) throw Error(rw + ".bin_width_diameters must be positive");
  if (!(s.slices >= 1 && s.slices <= 20 && s.slices == std::floor(s.slices)))
    throw Error(rw + ".slices must be a whole number in [1, 20]");
  return s;
}

// A vertical rectangle of two triangles between corners a and b (opposite), in mesh `mesh`.
void add_rectangle(std::vector<Wall>& walls, Vec3 a, Vec3 b, bool along_x, std::int32_t mesh) {
  const Vec3 c = along_x ? Vec3{b.x, a.y, a.z} : Vec3{a.x, b.y, a.z}, d{a.x, a.y, b.z};
  walls.push_back(make_triangle(a, c, b, mesh, a, kWallGroup));
  walls.push_back(make_triangle(a, b, d, mesh, a, kWallGroup));
}

std::string escaped(const World& world, const BaffleSpec& s) {
  const double margin = 2 * s.powder.radius_max_m, reach = s.domain_radius_m() + margin;
  const Spheres& sp = world.spheres;
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const Vec3 x = sp.position(i), v = sp.velocity(i);
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z))
      return "a particle's position or velocity is not finite at t = " + format_double(world.time_s()) + " s";
    if (x.z < -margin || std::hypot(x.x, x.y) > reach || x.z > 10 * s.height_m)
      return "a particle left the domain through a wall at t = " + format_double(world.time_s()) + " s (x " +
             format_double(x.x) + ", y " + format_double(x.y) + ", z " + format_double(x.z) + " m, moving at " +
             format_double(norm(v)) + " m/s): thrown faster than the walls' contacts stop it, or the time step is "
             "too large for the contacts";
  }
  return "";
}

// The slope in each slice across the measured band: the spheres inside the box whose centres lie in the slice,
// seen along y as a profile of height against x.
std::vector<dem::SlopeFit> fit_slices(const World& world, const BaffleSpec& s, dem::TestResult& result) {
  const auto n = static_cast<std::size_t>(s.slices);
  const double half_band = s.measured_half_width_m(), slice_m = 2 * half_band / static_cast<double>(n);
  std::vector<std::vector<double>> x(n), z(n), r(n);
  const Spheres& sp = world.spheres;
  std::size_t in_box = 0;
  for (std::size_t i = 0; i < sp.size(); ++i) {
    if (std::abs(sp.x[i]) > 0.5 * s.length_m || std::abs(sp.y[i]) > 0.5 * s.width_m) continue;
    ++in_box;
    if (std::abs(sp.y[i]) > half_band) continue;
    const auto k = std::min(n - 1, static_cast<std::size_t>((sp.y[i] + half_band) / slice_m));
    x[k].push_back(sp.x[i]);
    z[k].push_back(sp.z[i]);
    r[k].push_back(sp.radius[i]);
  }
  const double retained = static_cast<double>(in_box) / static_cast<double>(sp.size());
  result.specimen_info["retained_fraction"] = retained;
  // A powder cohesive enough stands where the baffle was: no slope, and no angle to report but a vertical face.
  if (retained > 0.99)
    throw Error("the powder did not run out: " + format_double(std::round(1000 * retained) / 10) +
                " % of it stayed in the box after the baffle rose, a face standing where the baffle was (no slope to "
                "fit; the cohesion holds it)");
  dem::ReposeOptions options;
  options.bin_width_m = s.bin_width_diameters * (s.powder.radius_min_m + s.powder.radius_max_m);
  std::vector<dem::SlopeFit> fits;
  for (std::size_t k = 0; k < n; ++k) {
    const std::string what = "the slope left in the box (slice " + std::to_string(k + 1) + " of " + std::to_string(n) + ")";
    if (x[k].empty()) throw Error(what + ": no powder left in the box");
    fits.push_back(dem::fit_slope(dem::surface_profile(x[k], z[k], r[k], 0.0, options.bin_width_m), options, what));
  }
  return fits;
}

dem::TestResult run_baffle_lift_3d(const Scene& scene, const std::map<std::string, double>& parameters,
                                   const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const BaffleSpec s = BaffleSpec::from_scene(scene, parameters);
  World world(powder_settings(scene, parameters, s.powder, s.stepping, options));
  bind_contact_models(world, scene, parameters);
  const double hx = 0.5 * s.length_m, hy = 0.5 * s.width_m, h = s.height_m;
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}, kWallGroup));  // the floor, under the box and the run-out
  add_rectangle(world.walls, {-hx, -hy, 0}, {-hx, hy, h}, false, kBackMesh);
  add_rectangle(world.walls, {-hx, -hy, 0}, {hx, -hy, h}, true, kLeftMesh);
  add_rectangle(world.walls, {-hx, hy, 0}, {hx, hy, h}, true, kRightMesh);
  const std::size_t baffle_begin = world.walls.size();
  add_rectangle(world.walls, {hx, -hy, 0}, {hx, hy, h}, false, kBaffleMesh);
  const std::size_t baffle_end = world.walls.size();
  world.walls.push_back(make_cylinder({0, 0, 0}, {0, 0, 1}, s.domain_radius_m(), 0, true, kWallGroup));

  const std::vector<PowderParticle3d> particles =
      place_powder_3d(s.powder, s.fill_region(), options.seed, scene.origin() + ": box (the fill)");
  add_powder_3d(world, particles, s.powder, kPowderGroup, options.particle_order_seed);
  world.refresh();

  dem::TestResult result;
  result.particles = world.spheres.size();
  result.specimen_info["particles"] = static_cast<double>(particles.size());
  result.specimen_info["clumps"] = static_cast<double>(world.clumps().size());
  dem::RunWatch watch("baffle lift", s.run.max_wall_s, start, s.run.max_time_s, "baffle_lift_3d (% of run.max_time_s)",
                      options.progress);
  const auto loading_start = std::chrono::steady_clock::now();
  const auto steps_per_check =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(s.run.check_every_s / world.dt_s())));
  enum class Stage { fill, lift, settle } stage = Stage::fill;
  auto set_baffle_speed = [&](double v) {
    for (std::size_t w = baffle_begin; w < baffle_end; ++w) world.walls[w].velocity_m_s = {0, 0, v};
  };
  result.ok = true;
  auto fail = [&](const std::string& why) {
    result.ok = false;
    result.reason = why;
  };
  for (;;) {
    world.run(steps_per_check);
    const double t = world.time_s();
    const std::string bad = escaped(world, s);
    if (!bad.empty()) {
      fail(bad);
      break;
    }
    if (!watch.carry_on(t)) {
      fail(watch.timeout_reason());
      break;
    }
    if (stage == Stage::fill && t >= s.run.fill_time_s) {
      double top = 0;
      for (std::size_t i = 0; i < world.spheres.size(); ++i)
        top = std::max(top, world.spheres.z[i] + world.spheres.radius[i]);
      result.specimen_info["bed_height_before_lift_m"] = top;
      set_baffle_speed(s.lift_speed_m_s);
      stage = Stage::lift;
    } else if (stage == Stage::lift && t >= s.lift_ends_at_s()) {
      set_baffle_speed(0);  // it stays up, out of the powder's way
      stage = Stage::settle;
    } else if (stage == Stage::settle && t >= s.settle_check_from_s()) {
      const double kinetic = world.kinetic_energy(), potential = potential_energy_j(world, 0.0);
      if (kinetic < s.run.settle_kinetic_ratio * potential) {
        result.specimen_info["kinetic_over_potential"] = kinetic / potential;
        break;
      }
    }
    if (t >= s.run.max_time_s) {
      fail("the powder did not settle within run.max_time_s " + format_double(s.run.max_time_s) +
           " s (kinetic / potential energy " + format_double(world.kinetic_energy() / potential_energy_j(world, 0.0)) +
           ", asked below " + format_double(s.run.settle_kinetic_ratio) + ")");
      break;
    }
  }
  watch.finish();
  finish_powder_run(world, scene, parameters, s.powder, options, start, loading_start, result);
  if (!result.ok) return result;

  std::vector<dem::SlopeFit> fits;
  try {
    fits = fit_slices(world, s, result);
  } catch (const Error& e) {
    result.ok = false;
    result.reason = e.what();
    return result;
  }
  double sum = 0;
  for (std::size_t k = 0; k < fits.size(); ++k) {
    sum += fits[k].deg;
    const std::string slice = "slice_" + std::to_string(k + 1);
    result.specimen_info["aor_" + slice + "_deg"] = fits[k].deg;
    result.specimen_info["aor_" + slice + "_r2"] = fits[k].r2;
    result.specimen_info["aor_" + slice + "_points"] = static_cast<double>(fits[k].points);
  }
  const double mean = sum / static_cast<double>(fits.size());
  double sum2 = 0;
  for (const dem::SlopeFit& f : fits) sum2 += (f.deg - mean) * (f.deg - mean);
  result.macro["aor_deg"] = mean;
  result.macro["aor_slices_sd_deg"] = fits.size() > 1 ? std::sqrt(sum2 / static_cast<double>(fits.size() - 1)) : 0.0;
  double highest = 0;
  for (std::size_t i = 0; i < world.spheres.size(); ++i)
    if (std::abs(world.spheres.x[i]) <= 0.5 * s.length_m && std::abs(world.spheres.y[i]) <= 0.5 * s.width_m)
      highest = std::max(highest, world.spheres.z[i] + world.spheres.radius[i]);
  result.macro["heap_height_m"] = highest;
  return result;
}

class BaffleLiftTest3d : public PowderTest3d {
 public:
  std::string name() const override { return "baffle_lift_3d"; }
  std::string description() const override {
    return "baffle lift in 3D: one side of a box of powder is lifted away; the static angle of the slope left in it";
  }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-wall", kWallGroup, "particles against the box's walls, the baffle, the floor and the domain"}};
  }
  // The test makes its particles in the box as it runs: no packed specimen, no loading.
  std::vector<dem::SceneSection> sections() const override {
    return {particles_section(),
            {"box", "the box, its loose fill and the floor beyond the baffle", false},
            {"baffle", "the baffle's lift", false},
            {"run", "time limits, the settling criterion, the slope's bins and slices", false}};
  }
  void check_scene(const Scene& scene) const override { BaffleSpec::from_scene(scene, scene.resolve({})); }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"aor_deg"}; }
  std::vector<dem::OutputSpec> outputs(const Scene&) const override {
    return {{"aor_deg", "deg", "static angle of repose of the slope left in the box: the mean over run.slices "
                               "slices across it of a least-squares line along the box, between 10 and 90 % of "
                               "the slice's height", true, dem::kAcuteAngleDeg},
            {"aor_slices_sd_deg", "deg", "the SD of the slices' angles", true, dem::kNonNegative},
            {"heap_height_m", "m", "the highest particle top left in the box, above the floor", true,
             dem::kNonNegative}};
  }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_baffle_lift_3d(scene, parameters, options);
  }
};

}  // namespace

void register_baffle_lift_test_3d(dem::LabTestRegistry& registry) {
  registry.add(std::make_unique<BaffleLiftTest3d>());
}

}  // namespace demcal::dem3d
