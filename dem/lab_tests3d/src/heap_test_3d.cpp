// The funnel heap in 3D (He et al. 2019's flow meter): a conical funnel
// filled with a powder of spheres or two-sphere clumps opens onto a round
// platform, stirred while it discharges by an optional brush of flat blades
// turning about its axis; what runs off the platform falls past its pedestal
// to a catch floor inside a cylindrical domain; once the heap has settled
// (kinetic energy below a set share of the potential), its angle of repose is
// fitted over vertical sections through the platform's axis
// (heap_section_fit.hpp), and the height-based angle taken from its height
// over the platform's radius. The outputs carry the 2D heap's names.
//
//   "particles": {"radius_min_m", "radius_max_m", "density_kg_m3", "clump_aspect_ratio" (1: spheres),
//                 "clump_fraction" (default 1)},
//   "funnel":    {"outlet_diameter_m", "wall_angle_deg" (from the horizontal, default 60), "height_m",
//                 "outlet_height_m" (above the platform), "fill_height_m" (default 0.8 x height),
//                 "solids_fraction" (default 0.25), "platform_diameter_m", "domain_diameter_m" (default 3 x platform),
//                 "facets" (around the funnel and the platform, default 48)},
//   "brush":     optional: {"rpm", "blades" (default 2), "clearance_m" (from the cone, default one particle
//                 length), "height_m" (its top above the outlet, default the fill height)},
//   "run":       {"max_time_s", "fill_time_s", "check_every_s", "settle_kinetic_ratio", "jam_time_s",
//                 "discharged_fraction", "local_damping", "max_wall_s", "bin_width_diameters", "sections",
//                 "safety_factor", "rayleigh_fraction" (a fixed step as this fraction of the Rayleigh step)}
//
// Contact roles: "particle-particle" and "particle-wall" (funnel, gate, brush, platform, pedestal, catch floor,
// domain).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/funnel_discharge.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem3d/heap_section_fit.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/powder_3d.hpp"
#include "demcal/dem3d/sphere_scene.hpp"
#include "powder_run.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::uint8_t kWallGroup = kPowderWallGroup;
constexpr std::int32_t kFunnelMesh = 0, kGateMesh = 1, kPlatformMesh = 2, kBrushMesh = 3;

// He's funnel had a brush turning at 60 rpm; its shape is not published. This
// one: flat blades in vertical planes through the axis, each reaching from
// the axis to `clearance_m` short of the cone, from the outlet up to
// `height_m`; it turns from the gate's opening until the funnel has
// discharged, then stops where it is (a turning blade would keep the powder
// caught on it moving and the heap from settling).
struct Brush {
  bool present = false;
  double rpm = 0, blades = 2, clearance_m = 0, height_m = 0;
};

struct HeapSpec3d {
  PowderSpec3d powder;
  double outlet_diameter_m = 0, wall_angle_deg = 60, funnel_height_m = 0, outlet_height_m = 0, fill_height_m = 0;
  double platform_diameter_m = 0, domain_diameter_m = 0, facets = 48;
  dem::FunnelRun run;  // the stages' keys of "run" (funnel_discharge.hpp)
  double bin_width_diameters = 1.5, sections = 8;
  PowderStepping stepping;
  Brush brush;

  // The cone's radius `above_outlet_m` above the outlet.
  double cone_radius_m(double above_outlet_m) const {
    return 0.5 * outlet_diameter_m + above_outlet_m / std::tan(wall_angle_deg * M_PI / 180);
  }
  double top_radius_m() const { return cone_radius_m(funnel_height_m); }
  // The catch floor's depth below the platform: room for the whole fill
  // spread over the ring between pedestal and domain (twice its packed
  // volume), and at least four particle lengths.
  double catch_depth_m() const {
    const Frustum fill = fill_region();
    const double ring = M_PI * 0.25 * (domain_diameter_m * domain_diameter_m - platform_diameter_m * platform_diameter_m);
    return std::max(4 * powder.longest_m(), 2 * powder.solids_fraction * fill.volume_m3() / 0.55 / ring);
  }
  // The funnel's inside up to the fill height, within the facets (a polygon
  // inscribed in the circle reaches in to cos(pi / facets) of its radius).
  Frustum fill_region() const {
    const double inscribed = std::cos(M_PI / facets);
    return {outlet_height_m, outlet_height_m + fill_height_m, inscribed * 0.5 * outlet_diameter_m,
            inscribed * cone_radius_m(fill_height_m)};
  }

  static HeapSpec3d from_scene(const Scene& scene, const std::map<std::string, double>& parameters);
};

HeapSpec3d HeapSpec3d::from_scene(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  HeapSpec3d s;
  auto number = [&](const std::string& section, const nlohmann::json& object, const char* key, double& target,
                    bool required) { dem::read_section_number(scene, parameters, section, object, key, target, required); };
  s.powder = read_powder_section(scene, parameters);

  const nlohmann::json& f = scene.section("funnel");
  require_known_fields(f, {"outlet_diameter_m", "wall_angle_deg", "height_m", "outlet_height_m", "fill_height_m",
                           "solids_fraction", "platform_diameter_m", "domain_diameter_m", "facets", "note"},
                       origin + ": funnel");
  number("funnel", f, "outlet_diameter_m", s.outlet_diameter_m, true);
  number("funnel", f, "wall_angle_deg", s.wall_angle_deg, false);
  number("funnel", f, "height_m", s.funnel_height_m, true);
  number("funnel", f, "outlet_height_m", s.outlet_height_m, true);
  s.fill_height_m = 0.8 * s.funnel_height_m;
  number("funnel", f, "fill_height_m", s.fill_height_m, false);
  number("funnel", f, "solids_fraction", s.powder.solids_fraction, false);
  number("funnel", f, "platform_diameter_m", s.platform_diameter_m, true);
  s.domain_diameter_m = 3 * s.platform_diameter_m;
  number("funnel", f, "domain_diameter_m", s.domain_diameter_m, false);
  number("funnel", f, "facets", s.facets, false);

  if (scene.has_section("brush")) {
    const nlohmann::json& b = scene.section("brush");
    require_known_fields(b, {"rpm", "blades", "clearance_m", "height_m", "note"}, origin + ": brush");
    s.brush.present = true;
    s.brush.clearance_m = s.powder.longest_m();
    s.brush.height_m = s.fill_height_m;
    number("brush", b, "rpm", s.brush.rpm, true);
    number("brush", b, "blades", s.brush.blades, false);
    number("brush", b, "clearance_m", s.brush.clearance_m, false);
    number("brush", b, "height_m", s.brush.height_m, false);
  }

  const nlohmann::json& r = scene.section("run");
  std::vector<std::string> run_keys = dem::FunnelRun::keys();
  run_keys.insert(run_keys.end(), PowderStepping::keys().begin(), PowderStepping::keys().end());
  run_keys.insert(run_keys.end(), {"bin_width_diameters", "sections", "note"});
  require_known_fields(r, run_keys, origin + ": run");
  s.run.read(scene, parameters, r);
  number("run", r, "bin_width_diameters", s.bin_width_diameters, false);
  number("run", r, "sections", s.sections, false);
  s.stepping.read(scene, parameters, r);

  s.powder.validate(origin + ": particles");
  const std::string fw = origin + ": funnel";
  const double length = s.powder.longest_m();
  // Below about four particle lengths an outlet arches and jams (Beverloo's empty annulus is 1.5 d on each side).
  if (!(s.outlet_diameter_m >= 4 * length))
    throw Error(fw + ".outlet_diameter_m " + format_double(s.outlet_diameter_m) + " m is less than 4 particle lengths (" +
                format_double(4 * length) + " m): the outlet would arch and jam");
  if (!(s.wall_angle_deg > 10 && s.wall_angle_deg < 90)) throw Error(fw + ".wall_angle_deg must lie in (10, 90)");
  if (!(s.funnel_height_m > 0)) throw Error(fw + ".height_m must be positive");
  if (!(s.fill_height_m > 0 && s.fill_height_m <= s.funnel_height_m))
    throw Error(fw + ".fill_height_m must lie in (0, height_m]");
  if (!(s.outlet_height_m >= 2 * length))
    throw Error(fw + ".outlet_height_m must be at least two particle lengths (" + format_double(2 * length) + " m)");
  if (!(s.platform_diameter_m > s.outlet_diameter_m)) throw Error(fw + ".platform_diameter_m must exceed outlet_diameter_m");
  if (!(s.domain_diameter_m > s.platform_diameter_m + 4 * length))
    throw Error(fw + ".domain_diameter_m " + format_double(s.domain_diameter_m) + " m must exceed platform_diameter_m " +
                format_double(s.platform_diameter_m) + " m by four particle lengths (what runs off the platform needs room)");
  if (2 * s.top_radius_m() > s.domain_diameter_m)
    throw Error(fw + ": the funnel's top, " + format_double(2 * s.top_radius_m()) + " m across, is wider than the "
                "domain (domain_diameter_m " + format_double(s.domain_diameter_m) + " m)");
  if (!(s.facets >= 12 && s.facets <= 720 && s.facets == std::floor(s.facets)))
    throw Error(fw + ".facets must be a whole number in [12, 720]");
  if (s.brush.present) {
    const std::string bw = origin + ": brush";
    if (!(s.brush.rpm > 0)) throw Error(bw + ".rpm must be positive");
    if (!(s.brush.blades >= 1 && s.brush.blades <= 12 && s.brush.blades == std::floor(s.brush.blades)))
      throw Error(bw + ".blades must be a whole number in [1, 12]");
    if (!(s.brush.height_m > 0 && s.brush.height_m <= s.funnel_height_m))
      throw Error(bw + ".height_m must lie in (0, funnel.height_m]");
    if (!(s.brush.clearance_m >= 0 && s.brush.clearance_m < 0.5 * s.outlet_diameter_m))
      throw Error(bw + ".clearance_m must lie in [0, half the outlet's diameter): the blades would not reach into "
                       "the outlet");
  }
  const std::string rw = origin + ": run";
  s.run.validate(rw);
  if (!(s.bin_width_diameters > 0)) throw Error(rw + ".bin_width_diameters must be positive");
  if (!(s.sections >= 1 && s.sections <= 90 && s.sections == std::floor(s.sections)))
    throw Error(rw + ".sections must be a whole number in [1, 90]");
  return s;
}

// A disk of `facets` triangles (a fan about its centre) at height z, radius r.
void add_disk(std::vector<Wall>& walls, double z, double r, int facets, std::int32_t mesh) {
  const Vec3 centre{0, 0, z};
  for (int k = 0; k < facets; ++k) {
    const double a = 2 * M_PI * k / facets, b = 2 * M_PI * (k + 1) / facets;
    walls.push_back(make_triangle(centre, {r * std::cos(a), r * std::sin(a), z}, {r * std::cos(b), r * std::sin(b), z},
                                  mesh, centre, kWallGroup));
  }
}

// The funnel's cone between the outlet (radius r0 at z0) and the top (r1 at z1): two triangles per facet.
void add_cone(std::vector<Wall>& walls, double z0, double r0, double z1, double r1, int facets) {
  const Vec3 pivot{0, 0, z0};
  for (int k = 0; k < facets; ++k) {
    const double a = 2 * M_PI * k / facets, b = 2 * M_PI * (k + 1) / facets;
    const Vec3 a0{r0 * std::cos(a), r0 * std::sin(a), z0}, b0{r0 * std::cos(b), r0 * std::sin(b), z0};
    const Vec3 a1{r1 * std::cos(a), r1 * std::sin(a), z1}, b1{r1 * std::cos(b), r1 * std::sin(b), z1};
    walls.push_back(make_triangle(a0, b0, b1, kFunnelMesh, pivot, kWallGroup));
    walls.push_back(make_triangle(a0, b1, a1, kFunnelMesh, pivot, kWallGroup));
  }
}

// The brush's blades (two triangles each), from the outlet up to its height, about the funnel's axis.
void add_brush(std::vector<Wall>& walls, const HeapSpec3d& s) {
  const double z0 = s.outlet_height_m, z1 = z0 + s.brush.height_m, c = s.brush.clearance_m;
  const double r0 = s.cone_radius_m(0) - c, r1 = s.cone_radius_m(s.brush.height_m) - c;
  const auto blades = static_cast<int>(s.brush.blades);
  for (int k = 0; k < blades; ++k) {
    const double a = 2 * M_PI * k / blades;
    const Vec3 out{std::cos(a), std::sin(a), 0};
    const Vec3 axis0{0, 0, z0}, axis1{0, 0, z1};
    walls.push_back(make_triangle(axis0, axis0 + r0 * out, axis1 + r1 * out, kBrushMesh, axis0, kWallGroup));
    walls.push_back(make_triangle(axis0, axis1 + r1 * out, axis1, kBrushMesh, axis0, kWallGroup));
  }
}

// Whether a particle's spheres keep clear of the brush's blades (by their radius).
bool clear_of_brush(const PowderParticle3d& p, const HeapSpec3d& s) {
  if (!s.brush.present) return true;
  const auto blades = static_cast<int>(s.brush.blades);
  for (const Vec3& x : member_centres(p, s.powder.clump_aspect_ratio)) {
    if (x.z > s.outlet_height_m + s.brush.height_m + p.radius_m) continue;
    for (int k = 0; k < blades; ++k) {
      const double a = 2 * M_PI * k / blades;
      // Distance from the blade's half-plane: across it where the centre lies on its side, else to its axis edge.
      const double along = x.x * std::cos(a) + x.y * std::sin(a), across = -x.x * std::sin(a) + x.y * std::cos(a);
      const double distance = along >= 0 ? std::abs(across) : std::hypot(along, across);
      if (distance < p.radius_m) return false;
    }
  }
  return true;
}

// Spheres whose centre is still above the outlet, less a radius (a clump counts by each member).
std::size_t in_funnel(const World& world, const HeapSpec3d& s) {
  const double level = s.outlet_height_m - s.powder.radius_max_m;
  return static_cast<std::size_t>(std::count_if(world.spheres.z.begin(), world.spheres.z.end(),
                                                [&](double z) { return z > level; }));
}

// Empty when the state is sane, else why the run fails.
std::string escaped(const World& world, const HeapSpec3d& s, double floor_z, double top_z) {
  const double margin = 2 * s.powder.radius_max_m, wall_r = 0.5 * s.domain_diameter_m + margin;
  const Spheres& sp = world.spheres;
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const Vec3 x = sp.position(i), v = sp.velocity(i);
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z))
      return "a particle's position or velocity is not finite at t = " + format_double(world.time_s()) + " s";
    if (x.z < floor_z - margin || std::hypot(x.x, x.y) > wall_r || x.z > top_z + 10 * s.funnel_height_m)
      return "a particle left the domain through a wall at t = " + format_double(world.time_s()) + " s (x " +
             format_double(x.x) + ", y " + format_double(x.y) + ", z " + format_double(x.z) + " m, moving at " +
             format_double(norm(v)) + " m/s): thrown faster than the walls' contacts stop it, or the time step is "
             "too large for the contacts";
  }
  return "";
}

dem::TestResult run_heap_3d(const Scene& scene, const std::map<std::string, double>& parameters,
                            const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const HeapSpec3d s = HeapSpec3d::from_scene(scene, parameters);
  const int facets = static_cast<int>(s.facets);
  const double ho = s.outlet_height_m, funnel_top = ho + s.funnel_height_m, floor_z = -s.catch_depth_m();
  const double r_platform = 0.5 * s.platform_diameter_m, r_domain = 0.5 * s.domain_diameter_m;

  World world(powder_settings(scene, parameters, s.powder, s.stepping, options));
  bind_contact_models(world, scene, parameters);
  add_cone(world.walls, ho, 0.5 * s.outlet_diameter_m, funnel_top, s.top_radius_m(), facets);
  const std::size_t gate_begin = world.walls.size();
  add_disk(world.walls, ho, 0.5 * s.outlet_diameter_m, facets, kGateMesh);
  const std::size_t gate_end = world.walls.size();
  if (s.brush.present) add_brush(world.walls, s);
  const std::size_t brush_end = world.walls.size();
  const auto turn_brush = [&](double rad_s) {
    for (std::size_t w = gate_end; w < brush_end; ++w) world.walls[w].spin_rad_s = {0, 0, rad_s};
  };
  // The turns the brush made, from its first blade's outer corner (each check's angle unwrapped).
  double brush_turns = 0, brush_angle = 0;
  const auto count_brush_turns = [&] {
    if (!s.brush.present) return;
    const Vec3 corner = world.walls[gate_end].vertices[1];
    const double angle = std::atan2(corner.y, corner.x);
    brush_turns += std::remainder(angle - brush_angle, 2 * M_PI) / (2 * M_PI);
    brush_angle = angle;
  };
  add_disk(world.walls, 0.0, r_platform, facets, kPlatformMesh);
  world.walls.push_back(make_cylinder({0, 0, floor_z}, {0, 0, 1}, r_platform, -floor_z, false, kWallGroup));  // pedestal
  world.walls.push_back(make_plane({0, 0, floor_z}, {0, 0, 1}, kWallGroup));                                  // catch floor
  world.walls.push_back(make_cylinder({0, 0, floor_z}, {0, 0, 1}, r_domain, funnel_top - floor_z, true, kWallGroup));

  std::vector<PowderParticle3d> particles =
      place_powder_3d(s.powder, s.fill_region(), options.seed, scene.origin() + ": funnel (the fill)");
  // The fill leaves the blades' places empty (a sphere placed across a blade would be thrown off it).
  const std::size_t placed = particles.size();
  particles.erase(std::remove_if(particles.begin(), particles.end(),
                                 [&](const PowderParticle3d& p) { return !clear_of_brush(p, s); }),
                  particles.end());
  add_powder_3d(world, particles, s.powder, kPowderGroup, options.particle_order_seed);
  world.refresh();

  dem::TestResult result;
  result.particles = world.spheres.size();
  result.specimen_info["particles"] = static_cast<double>(particles.size());
  result.specimen_info["clumps"] = static_cast<double>(world.clumps().size());
  result.specimen_info["catch_depth_m"] = -floor_z;
  if (s.brush.present) result.specimen_info["left_out_for_brush"] = static_cast<double>(placed - particles.size());
  const auto loading_start = std::chrono::steady_clock::now();
  const auto steps_per_check =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(s.run.check_every_s / world.dt_s())));
  dem::FunnelDischarge stages(s.run, world.spheres.size(), {"heap", "heap_3d", "spheres", "funnel.outlet_diameter_m"}, start,
                              options.progress);
  const auto in_funnel_now = [&] { return in_funnel(world, s); };
  const auto energies = [&] { return std::pair{world.kinetic_energy(), potential_energy_j(world, floor_z)}; };
  stages.run(
      result,
      [&] {
        if (s.brush.present && stages.flow_time_s() >= 0) turn_brush(0.0);  // discharged: the brush stops
        world.run(steps_per_check);
        count_brush_turns();
        return world.time_s();
      },
      [&] { return escaped(world, s, floor_z, funnel_top); },
      [&] {
        for (std::size_t w = gate_begin; w < gate_end; ++w) world.walls[w].active = false;
        if (s.brush.present) turn_brush(s.brush.rpm * 2 * M_PI / 60);
        world.refresh();
      },
      in_funnel_now, energies);
  if (s.brush.present) result.specimen_info["brush_turns"] = brush_turns;
  finish_powder_run(world, scene, parameters, s.powder, options, start, loading_start, result);
  if (!result.ok) return result;

  // The heap: the spheres above the platform, below the outlet.
  std::vector<double> x, y, z, r;
  const Spheres& sp = world.spheres;
  for (std::size_t i = 0; i < sp.size(); ++i)
    if (sp.z[i] > 0 && sp.z[i] < ho - s.powder.radius_max_m &&
        std::hypot(sp.x[i], sp.y[i]) <= r_platform + s.powder.radius_max_m) {
      x.push_back(sp.x[i]);
      y.push_back(sp.y[i]);
      z.push_back(sp.z[i]);
      r.push_back(sp.radius[i]);
    }
  HeapSectionOptions fit_options;
  fit_options.sections = static_cast<std::size_t>(s.sections);
  const double diameter = s.powder.radius_min_m + s.powder.radius_max_m;
  fit_options.profile.bin_width_m = s.bin_width_diameters * diameter;
  // A section two particles thick: thinner ones leave bins of the surface empty.
  fit_options.slab_width_m = std::max(fit_options.profile.bin_width_m, 2 * diameter);
  try {
    const HeapSectionFit fit = fit_heap_sections(x, y, z, r, 0.0, fit_options);
    if (fit.height_m > ho - 2 * s.powder.radius_max_m)
      throw Error("the heap reached the funnel's outlet (height " + format_double(fit.height_m) +
                  " m): raise funnel.outlet_height_m or widen funnel.platform_diameter_m");
    result.macro["aor_deg"] = fit.mean_deg;
    result.macro["aor_sections_sd_deg"] = fit.sd_deg;
    result.macro["heap_height_m"] = fit.height_m;
    // The height-based angle of a cone on a round plate: tan = height / radius.
    result.macro["aor_fixed_base_deg"] = std::atan(fit.height_m / r_platform) * 180.0 / M_PI;
    result.macro["flow_time_s"] = stages.flow_time_s();
    bool covers = true;  // every section's profile reaches both edges of the plate
    for (const dem::ReposeFit& f : fit.sections)
      covers = covers && !f.profile_x_m.empty() && f.profile_x_m.front() <= -r_platform + fit_options.profile.bin_width_m &&
               f.profile_x_m.back() >= r_platform - fit_options.profile.bin_width_m;
    result.specimen_info["heap_covers_plate"] = covers ? 1.0 : 0.0;
    result.specimen_info["heap_spheres"] = static_cast<double>(x.size());
    result.specimen_info["settled_at_s"] = world.time_s();
    // The first section's profile as the result's curve: the distance along
    // it in axial_strain's column, the surface height in lateral_strain's.
    const dem::ReposeFit& first = fit.sections.front();
    for (std::size_t k = 0; k < first.profile_x_m.size(); ++k) {
      dem::CurvePoint point;
      point.axial_strain = first.profile_x_m[k];
      point.lateral_strain = first.profile_height_m[k];
      result.curve.push_back(point);
    }
  } catch (const Error& e) {
    result.ok = false;
    result.reason = e.what();
  }
  return result;
}

class HeapTest3d : public PowderTest3d {
 public:
  std::string name() const override { return "heap_3d"; }
  std::string description() const override {
    return "funnel heap in 3D: a conical funnel of powder opens onto a round platform; the settled heap's angle of "
           "repose over vertical sections, and its height-based angle";
  }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-wall", kWallGroup, "particles against the funnel, its gate and brush, the platform and the catch floor"}};
  }
  // The heap makes its particles in the funnel as it runs: no packed specimen, no loading.
  std::vector<dem::SceneSection> sections() const override {
    return {particles_section(),
            {"funnel", "the funnel, the platform and the domain", false},
            {"brush", "the funnel's stirring brush (optional: none without it)", false},
            {"run", "time limits, the settling criterion, the angle's bins and sections", false}};
  }
  void check_scene(const Scene& scene) const override { HeapSpec3d::from_scene(scene, scene.resolve({})); }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"aor_deg", "aor_fixed_base_deg"}; }
  std::vector<dem::OutputSpec> outputs(const Scene&) const override {
    return {{"aor_deg", "deg", "angle of repose, the mean over both flanks of run.sections vertical sections through "
                               "the platform's axis (least-squares lines between 10 and 90 % of each section's height)",
             true, dem::kAcuteAngleDeg},
            {"aor_sections_sd_deg", "deg", "the SD of the flank angles around the heap", true, dem::kNonNegative},
            {"heap_height_m", "m", "the settled heap's height above the platform", true, dem::kNonNegative},
            {"aor_fixed_base_deg", "deg", "the height-based angle, atan(heap_height_m / the platform's radius); the "
                                          "specimen's heap_covers_plate says whether the flanks reach its edge",
             true, dem::kAcuteAngleDeg},
            {"flow_time_s", "s", "time from opening the outlet until run.discharged_fraction of the spheres left the funnel",
             true, dem::kNonNegative}};
  }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_heap_3d(scene, parameters, options);
  }
};

}  // namespace

void register_heap_test_3d(dem::LabTestRegistry& registry) { registry.add(std::make_unique<HeapTest3d>()); }

}  // namespace demcal::dem3d
