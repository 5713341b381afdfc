// Heap test: a funnel discharges a powder onto a raised base; the settled
// heap's angle of repose and the funnel's discharge time (heap_test.hpp).
#include "demcal/dem/heap_test.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/angle_of_repose.hpp"
#include "demcal/dem/cohesion_number.hpp"
#include "demcal/dem/builtin_tests.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/funnel_discharge.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/run_settings.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

constexpr std::uint8_t kPowderGroup = 0, kWallGroup = 1;
constexpr double kGravity_m_s2 = 9.81;

// Wall indices, in the order make_heap_world adds them.
enum HeapWall : std::size_t { kBase = 0, kBaseLeft, kBaseRight, kCatchFloor, kDomainLeft, kDomainRight, kFunnelLeft,
                              kFunnelRight, kGate, kHeapWalls };

Wall segment(const char* name, double x0, double y0, double x1, double y1) {
  Wall w;
  w.name = name;
  w.x0 = x0;
  w.y0 = y0;
  w.x1 = x1;
  w.y1 = y1;
  w.group = kWallGroup;
  return w;
}

// The catch floor's depth below the base: room for everything the funnel
// holds between the base's sides and the domain's (twice its packed area),
// and at least four particle lengths.
double catch_depth_m(const HeapSpec& s) {
  const double fill_area = 0.5 * (s.outlet_width_m + s.outlet_width_m + 2 * s.fill_height_m / std::tan(s.wall_angle_deg * M_PI / 180)) *
                           s.fill_height_m;
  const double length = 2 * s.powder.radius_max_m * s.powder.clump_aspect_ratio;
  return std::max(4 * length, 2 * fill_area / (s.domain_width_m - s.base_width_m));
}

// Moving bodies: a clump counts once (its centre and mass), a free disk as itself.
template <typename F>
void for_each_particle(const World& world, F f) {
  for (const Clump& c : world.clumps()) f(c.x, c.y, c.mass);
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (world.bodies.clump[i] < 0 && !world.bodies.fixed[i]) f(world.bodies.x[i], world.bodies.y[i], world.bodies.mass[i]);
}

double potential_energy_j(const World& world, double floor_y) {
  double energy = 0;
  for_each_particle(world, [&](double, double y, double m) { energy += m * kGravity_m_s2 * (y - floor_y); });
  return energy;
}

// Particles whose centre is still above the outlet (less a particle radius).
std::size_t in_funnel(const World& world, const HeapSpec& s) {
  std::size_t count = 0;
  const double level = s.outlet_height_m - s.powder.radius_max_m;
  for_each_particle(world, [&](double, double y, double) { count += y > level; });
  return count;
}

// Empty when the state is sane, else why the run fails.
std::string escaped(const World& world, const HeapSpec& s, double floor_y, double top_y) {
  const double margin = 2 * s.powder.radius_max_m;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const double x = world.bodies.x[i], y = world.bodies.y[i];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(world.bodies.vx[i]) || !std::isfinite(world.bodies.vy[i]))
      return "a particle's position or velocity is not finite at t = " + format_double(world.time_s()) + " s";
    if (y < floor_y - margin || std::abs(x) > 0.5 * s.domain_width_m + margin || y > top_y + 10 * s.funnel_height_m)
      return "a particle left the domain through a wall at t = " + format_double(world.time_s()) +
             " s (x " + format_double(x) + " m, y " + format_double(y) + " m): the time step is too large for the contacts";
  }
  return "";
}

}  // namespace

double HeapSpec::top_width_m() const {
  return outlet_width_m + 2 * funnel_height_m / std::tan(wall_angle_deg * M_PI / 180);
}

HeapSpec HeapSpec::from_scene(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  HeapSpec s;
  auto number = [&](const std::string& section, const nlohmann::json& object, const char* key, double& target,
                    bool required) { read_section_number(scene, parameters, section, object, key, target, required); };
  const nlohmann::json& p = scene.section("particles");
  require_known_fields(p, {"radius_min_m", "radius_max_m", "density_kg_m3", "thickness_m", "clump_aspect_ratio",
                           "clump_fraction", "note"},
                       origin + ": particles");
  number("particles", p, "radius_min_m", s.powder.radius_min_m, true);
  number("particles", p, "radius_max_m", s.powder.radius_max_m, true);
  number("particles", p, "density_kg_m3", s.powder.density_kg_m3, true);
  s.thickness_m = s.powder.radius_min_m + s.powder.radius_max_m;  // the mean diameter
  number("particles", p, "thickness_m", s.thickness_m, false);
  number("particles", p, "clump_aspect_ratio", s.powder.clump_aspect_ratio, false);
  number("particles", p, "clump_fraction", s.powder.clump_fraction, false);

  const nlohmann::json& f = scene.section("funnel");
  require_known_fields(f, {"outlet_width_m", "wall_angle_deg", "height_m", "outlet_height_m", "fill_height_m",
                           "solids_fraction", "base_width_m", "domain_width_m", "note"},
                       origin + ": funnel");
  number("funnel", f, "outlet_width_m", s.outlet_width_m, true);
  number("funnel", f, "wall_angle_deg", s.wall_angle_deg, false);
  number("funnel", f, "height_m", s.funnel_height_m, true);
  number("funnel", f, "outlet_height_m", s.outlet_height_m, true);
  s.fill_height_m = 0.8 * s.funnel_height_m;
  number("funnel", f, "fill_height_m", s.fill_height_m, false);
  number("funnel", f, "solids_fraction", s.powder.solids_fraction, false);
  number("funnel", f, "base_width_m", s.base_width_m, true);
  s.domain_width_m = 3 * s.base_width_m;
  number("funnel", f, "domain_width_m", s.domain_width_m, false);

  const nlohmann::json& r = scene.section("run");
  std::vector<std::string> run_keys = FunnelRun::keys();
  run_keys.insert(run_keys.end(), {"local_damping", "bin_width_diameters", "safety_factor", "note"});
  require_known_fields(r, run_keys, origin + ": run");
  s.run.read(scene, parameters, r);
  number("run", r, "local_damping", s.local_damping, false);
  number("run", r, "bin_width_diameters", s.bin_width_diameters, false);
  number("run", r, "safety_factor", s.safety_factor, false);

  s.powder.validate((origin + ": particles").c_str());
  const std::string fw = origin + ": funnel";
  if (!(s.thickness_m > 0)) throw Error(origin + ": particles.thickness_m must be positive");
  const double length = 2 * s.powder.radius_max_m * s.powder.clump_aspect_ratio;  // the longest particle
  // Below about four particle lengths an outlet arches and jams (Beverloo's empty annulus is 1.5 d on each side).
  if (!(s.outlet_width_m >= 4 * length))
    throw Error(fw + ".outlet_width_m " + format_double(s.outlet_width_m) + " m is less than 4 particle lengths (" +
                format_double(4 * length) + " m): the outlet would arch and jam");
  if (!(s.wall_angle_deg > 10 && s.wall_angle_deg <= 90)) throw Error(fw + ".wall_angle_deg must lie in (10, 90]");
  if (!(s.funnel_height_m > 0)) throw Error(fw + ".height_m must be positive");
  if (!(s.fill_height_m > 0 && s.fill_height_m <= s.funnel_height_m))
    throw Error(fw + ".fill_height_m must lie in (0, height_m]");
  if (!(s.outlet_height_m >= 2 * length))
    throw Error(fw + ".outlet_height_m must be at least two particle lengths (" + format_double(2 * length) + " m)");
  if (!(s.base_width_m > s.outlet_width_m)) throw Error(fw + ".base_width_m must exceed outlet_width_m");
  if (!(s.domain_width_m > s.base_width_m))
    throw Error(fw + ".domain_width_m " + format_double(s.domain_width_m) + " m must exceed base_width_m " +
                format_double(s.base_width_m) + " m (what runs off the base needs room)");
  if (s.top_width_m() > s.domain_width_m)
    throw Error(fw + ": the funnel's top, " + format_double(s.top_width_m()) + " m wide (outlet_width_m + 2 height_m / "
                "tan wall_angle_deg), is wider than the domain (domain_width_m " + format_double(s.domain_width_m) + " m)");
  const std::string rw = origin + ": run";
  s.run.validate(rw);
  if (!(s.local_damping >= 0 && s.local_damping < 1)) throw Error(rw + ".local_damping must lie in [0, 1)");
  if (!(s.bin_width_diameters > 0)) throw Error(rw + ".bin_width_diameters must be positive");
  if (!(s.safety_factor > 0 && s.safety_factor <= 1)) throw Error(rw + ".safety_factor must lie in (0, 1]");
  return s;
}

// The particle-particle work of adhesion the contacts use (the scaled surface
// energy) and the cohesion number it gives these particles, so a result says
// which cohesion it ran at; nothing when the particles are not cohesive (JKR).
void report_cohesion(const Scene& scene, const std::map<std::string, double>& parameters, const HeapSpec& s,
                     TestResult& result) {
  auto it = scene.contacts().find("particle-particle");
  if (it == scene.contacts().end() || it->second.model != "jkr") return;
  const nlohmann::json bound = scene.bind(it->second, parameters, scene.origin() + ": contacts.particle-particle");
  const double w = bound.at("work_of_adhesion_j_m2").get<double>();
  const double e_star = effective_modulus_pa(bound.at("shear_modulus_pa").get<double>(), bound.at("poisson").get<double>());
  const double r_star = 0.25 * (s.powder.radius_min_m + s.powder.radius_max_m);  // two particles of the mean radius
  result.specimen_info["work_of_adhesion_j_m2"] = w;
  result.specimen_info["cohesion_number"] = cohesion_number(w, e_star, r_star, s.powder.density_kg_m3, kGravity_m_s2);
}

TestResult run_heap(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const HeapSpec s = HeapSpec::from_scene(scene, parameters);
  const double tan_a = std::tan(s.wall_angle_deg * M_PI / 180);
  const double ho = s.outlet_height_m, half_out = 0.5 * s.outlet_width_m, half_top = 0.5 * s.top_width_m();
  const double funnel_top = ho + s.funnel_height_m, depth = catch_depth_m(s), floor_y = -depth;
  const double half_base = 0.5 * s.base_width_m, half_domain = 0.5 * s.domain_width_m;

  WorldSettings settings;
  settings.thickness_m = s.thickness_m;
  settings.damping = s.local_damping;
  settings.safety_factor = s.safety_factor;
  settings.gravity_y_m_s2 = -kGravity_m_s2;
  apply_run_options(settings, options);
  World world(settings);
  bind_contact_models(world, scene, parameters);
  world.walls = {segment("base", -half_base, 0, half_base, 0),
                 segment("base_left_side", -half_base, 0, -half_base, floor_y),
                 segment("base_right_side", half_base, 0, half_base, floor_y),
                 segment("catch_floor", -half_domain, floor_y, half_domain, floor_y),
                 segment("domain_left", -half_domain, floor_y, -half_domain, funnel_top),
                 segment("domain_right", half_domain, floor_y, half_domain, funnel_top),
                 segment("funnel_left", -half_out, ho, -half_top, funnel_top),
                 segment("funnel_right", half_out, ho, half_top, funnel_top),
                 segment("gate", -half_out, ho, half_out, ho)};

  // The fill: the funnel's inside up to the fill height, counter-clockwise.
  const double fill_top = ho + s.fill_height_m, half_fill = half_out + s.fill_height_m / tan_a;
  const std::vector<double> region = {-half_out, ho, half_out, ho, half_fill, fill_top, -half_fill, fill_top};
  const std::vector<PowderParticle> particles = place_powder(s.powder, region, options.seed);
  add_powder(world, particles, s.powder, s.thickness_m, kPowderGroup, options.particle_order_seed);
  world.refresh();

  TestResult result;
  result.particles = world.bodies.size();
  result.specimen_info["particles"] = static_cast<double>(particles.size());
  result.specimen_info["clumps"] = static_cast<double>(world.clumps().size());
  result.specimen_info["catch_depth_m"] = depth;
  report_cohesion(scene, parameters, s, result);
  const auto loading_start = std::chrono::steady_clock::now();
  const std::uint64_t steps_per_check =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(s.run.check_every_s / world.dt_s())));
  FunnelDischarge stages(s.run, particles.size(), {"heap", "heap", "particles", "funnel.outlet_width_m"}, start,
                         options.progress);
  const auto in_funnel_now = [&] { return in_funnel(world, s); };
  const auto energies = [&] { return std::pair{world.kinetic_energy(), potential_energy_j(world, floor_y)}; };
  stages.run(
      result,
      [&] {
        world.run(steps_per_check);
        return world.time_s();
      },
      [&] { return escaped(world, s, floor_y, funnel_top); },
      [&] {
        world.walls[kGate].active = false;
        world.refresh();
      },
      in_funnel_now, energies);
  record_run_timing(world, options, start, loading_start, result);  // nothing is bonded: no crack counts
  if (!result.ok) return result;

  // The heap: the disks on the base, below the outlet.
  std::vector<double> x, y, r;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const double xi = world.bodies.x[i], yi = world.bodies.y[i];
    if (yi > 0 && yi < ho - s.powder.radius_max_m && std::abs(xi) <= half_base + s.powder.radius_max_m) {
      x.push_back(xi);
      y.push_back(yi);
      r.push_back(world.bodies.radius[i]);
    }
  }
  ReposeOptions fit_options;
  fit_options.bin_width_m = s.bin_width_diameters * (s.powder.radius_min_m + s.powder.radius_max_m);
  try {
    const ReposeFit fit = fit_angle_of_repose(x, y, r, 0.0, fit_options);
    if (fit.height_m > ho - 2 * s.powder.radius_max_m)
      throw Error("the heap reached the funnel's outlet (height " + format_double(fit.height_m) +
                  " m): raise funnel.outlet_height_m or widen funnel.base_width_m");
    result.macro["aor_deg"] = fit.mean_deg;
    result.macro["aor_left_deg"] = fit.left_deg;
    result.macro["aor_right_deg"] = fit.right_deg;
    result.macro["heap_height_m"] = fit.height_m;
    // The fixed-base method's angle (a cone on a plate of known width, as in
    // ISO 4324): tan = height / half the plate. It takes the flanks to reach
    // the plate's edges, which heap_covers_plate says. The height scatters far
    // less from seed to seed than the flanks' fits of a cohesive heap do.
    result.macro["aor_fixed_base_deg"] = std::atan(fit.height_m / half_base) * 180.0 / M_PI;
    const bool covers = !fit.profile_x_m.empty() && fit.profile_x_m.front() <= -half_base + fit_options.bin_width_m &&
                        fit.profile_x_m.back() >= half_base - fit_options.bin_width_m;
    result.specimen_info["heap_covers_plate"] = covers ? 1.0 : 0.0;
    result.macro["flow_time_s"] = stages.flow_time_s();
    result.specimen_info["heap_disks"] = static_cast<double>(x.size());
    result.specimen_info["aor_left_r2"] = fit.left_r2;
    result.specimen_info["aor_right_r2"] = fit.right_r2;
    // The fitted lines, height = intercept + slope x (scripts/plot_heap.py draws them).
    result.specimen_info["aor_left_slope"] = fit.left_slope;
    result.specimen_info["aor_left_intercept_m"] = fit.left_intercept_m;
    result.specimen_info["aor_right_slope"] = fit.right_slope;
    result.specimen_info["aor_right_intercept_m"] = fit.right_intercept_m;
    result.specimen_info["settled_at_s"] = world.time_s();
    // The profile and the fitted flanks as the result's curve: x along the
    // base in axial_strain's column, surface height in lateral_strain's.
    for (std::size_t k = 0; k < fit.profile_x_m.size(); ++k) {
      CurvePoint point;
      point.axial_strain = fit.profile_x_m[k];
      point.lateral_strain = fit.profile_height_m[k];
      result.curve.push_back(point);
    }
  } catch (const Error& e) {
    result.ok = false;
    result.reason = e.what();
  }
  return result;
}

namespace {

class HeapTest : public LabTest {
 public:
  std::string name() const override { return "heap"; }
  std::string description() const override {
    return "fixed-funnel heap: a funnel of powder opens onto a raised base; the settled heap's angle of repose";
  }
  std::vector<BoundaryRole> boundary_roles() const override {
    return {{"particle-wall", kWallGroup, "particles against the funnel, the base and the catch floor"}};
  }
  bool exact_scaling() const override { return false; }  // gravity sets the stresses
  // 1: aor_fixed_base_deg joined the outputs (stored heaps without it run again).
  int results_version() const override { return 1; }
  int dimension() const override { return 2; }
  const ContactModelCatalog& contact_models() const override { return disk_contact_models(); }
  // The heap makes its particles in the funnel as it runs: no packed specimen, no loading.
  std::vector<SceneSection> sections() const override {
    return {{"particles", "the powder: radii, density, thickness, clumps", true, true},
            {"funnel", "the funnel, the base and the domain", false},
            {"run", "time limits, the settling criterion, the angle's bins", false}};
  }
  std::vector<ContactRole> specimen_roles(const Scene&) const override {
    return {{"particle-particle", {{kPowderGroup, kPowderGroup}}, "particles against each other"}};
  }
  void check_scene(const Scene& scene) const override { HeapSpec::from_scene(scene, scene.resolve({})); }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"aor_deg", "aor_fixed_base_deg"}; }
  std::pair<std::string, std::string> curve_axes() const override { return {"", ""}; }  // a profile, not a curve
  std::vector<OutputSpec> outputs(const Scene&) const override {
    return {{"aor_deg", "deg", "angle of repose, the mean of both flanks' least-squares lines between 10 and 90 % of the "
                               "heap's height", true, kAcuteAngleDeg},
            {"aor_left_deg", "deg", "the left flank's angle", true, kAcuteAngleDeg},
            {"aor_right_deg", "deg", "the right flank's angle", true, kAcuteAngleDeg},
            {"heap_height_m", "m", "the settled heap's height above the base", true, kNonNegative},
            {"aor_fixed_base_deg", "deg", "the fixed-base method's angle, atan(heap_height_m / half of funnel.base_width_m); "
                                          "the specimen's heap_covers_plate says whether the flanks reach the plate's edges", true, kAcuteAngleDeg},
            {"flow_time_s", "s", "time from opening the outlet until run.discharged_fraction of the particles left the funnel", true,
             kNonNegative}};
  }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_heap(scene, parameters, options);
  }
};

}  // namespace

void register_heap_test(LabTestRegistry& registry) { registry.add(std::make_unique<HeapTest>()); }

}  // namespace demcal::dem
