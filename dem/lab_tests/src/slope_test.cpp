// Slope test: a bedrock-and-rockfill section at rest under gravity, its walls
// replaced by viscous and input boundaries, a wave in through the input side,
// monitoring points that record how the slope rings and falls quiet
// (slope_test.hpp).
#include "demcal/dem/slope_test.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/builtin_tests.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/equilibrium.hpp"
#include "demcal/dem/ground_motion.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/particle_order.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/run_settings.hpp"
#include "demcal/dem/slope_state.hpp"
#include "demcal/dem/vtk_writer.hpp"
#include "demcal/dem/wave_signals.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

constexpr std::uint8_t kBedrockGroup = 0, kRockfillGroup = 1, kWallGroup = 2;
// A disk within this share of its radius of a wall at rest is a boundary disk: the bonded bedrock settles a few
// millimetres off the frictionless walls in places, and a gap in the boundary would leave its edge undamped.
constexpr double kNearWallGap = 0.05;
// Inward unit normal of each side (bottom, left, right).
constexpr std::array<std::array<double, 2>, 3> kInward = {{{0, 1}, {1, 0}, {-1, 0}}};

Profile read_profile(const nlohmann::json& v, const std::string& where) {
  if (!v.is_array()) throw Error(where + ": must be a list of points [x_m, y_m]");
  Profile p;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const nlohmann::json& point = v[k];
    if (!point.is_array() || point.size() != 2 || !point[0].is_number() || !point[1].is_number())
      throw Error(where + "[" + std::to_string(k) + "]: must be [x_m, y_m]");
    p.x.push_back(point[0].get<double>());
    p.y.push_back(point[1].get<double>());
  }
  p.validate(where);
  return p;
}

SlopePart read_part(const Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& o,
                    const std::string& where, std::initializer_list<const char*> more_keys) {
  std::vector<std::string> keys = {"radius_min_m", "radius_max_m", "porosity", "density_kg_m3", "note"};
  for (const char* k : more_keys) keys.push_back(k);
  require_known_fields(o, keys, scene.origin() + ": " + where);
  SlopePart p;
  read_section_number(scene, parameters, where, o, "radius_min_m", p.radius_min_m, true);
  read_section_number(scene, parameters, where, o, "radius_max_m", p.radius_max_m, true);
  read_section_number(scene, parameters, where, o, "porosity", p.porosity, false);
  read_section_number(scene, parameters, where, o, "density_kg_m3", p.density_kg_m3, true);
  return p;
}

EarthquakeSpec read_earthquake(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  const nlohmann::json& e = scene.section("earthquake");
  require_known_fields(e, {"record_file", "format", "time_step_s", "units", "scale", "duration_s", "wave", "baseline", "note"},
                       origin + ": earthquake");
  EarthquakeSpec q;
  if (!e.contains("record_file") || !e.at("record_file").is_string())
    throw Error(origin + ": earthquake.record_file: missing (the acceleration record, relative to the scene file's folder)");
  const std::filesystem::path file = e.at("record_file").get<std::string>();
  q.record_path = (file.is_absolute() ? file : std::filesystem::path(origin).parent_path() / file).string();
  auto choice = [&](const char* key, std::initializer_list<const char*> allowed, const char* fallback) {
    if (!e.contains(key)) return std::string(fallback);
    const nlohmann::json& v = e.at(key);
    for (const char* a : allowed)
      if (v == a) return std::string(a);
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
    throw Error(origin + ": earthquake." + key + ": " + v.dump() + " (allowed: " + list + ")");
  };
  q.format = choice("format", {"values", "time_value"}, "values") == "values" ? RecordFormat::values : RecordFormat::time_value;
  q.to_m_s2 = choice("units", {"g", "m/s2"}, "g") == "g" ? 9.80665 : 1.0;
  q.s_wave = choice("wave", {"s", "p"}, "s") == "s";
  q.baseline = choice("baseline", {"end_at_rest", "none"}, "end_at_rest") == "end_at_rest" ? Baseline::end_at_rest : Baseline::none;
  read_section_number(scene, parameters, "earthquake", e, "time_step_s", q.time_step_s, false);
  read_section_number(scene, parameters, "earthquake", e, "scale", q.scale, false);
  read_section_number(scene, parameters, "earthquake", e, "duration_s", q.duration_s, false);
  if (e.contains("time_step_s") && !(q.time_step_s > 0)) throw Error(origin + ": earthquake.time_step_s must be positive");
  if (!(q.duration_s >= 0)) throw Error(origin + ": earthquake.duration_s must be >= 0 (0: the whole record)");
  if (!std::isfinite(q.scale)) throw Error(origin + ": earthquake.scale must be a finite number");
  // Read now, so a bad record fails when the scene is read, before any run.
  double step = q.time_step_s;
  const std::vector<double> record = read_acceleration_record(q.record_path, q.format, step, origin + ": earthquake");
  q.motion = ground_motion(record, step, q.to_m_s2 * q.scale, q.duration_s, q.baseline);
  return q;
}

}  // namespace

std::string slope_output_label(const std::string& label) {
  std::string out = label;
  std::replace(out.begin(), out.end(), '-', '_');
  return out;
}

SlopeTestSpec SlopeTestSpec::from_scene(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  SlopeTestSpec s;
  auto number = [&](const std::string& section, const nlohmann::json& object, const char* key, double& target,
                    bool required) { read_section_number(scene, parameters, section, object, key, target, required); };

  // The section's geometry and its parts.
  const nlohmann::json& g = scene.section("slope");
  require_known_fields(g, {"width_m", "height_m", "thickness_m", "column_width_m", "bond_gap_tolerance_m", "bedrock",
                           "zones", "note"},
                       origin + ": slope");
  SlopeSpec& geo = s.geometry;
  number("slope", g, "width_m", geo.width_m, true);
  number("slope", g, "height_m", geo.height_m, true);
  number("slope", g, "thickness_m", geo.thickness_m, false);
  number("slope", g, "column_width_m", geo.column_width_m, false);
  number("slope", g, "bond_gap_tolerance_m", s.bond_gap_tolerance_m, false);
  if (s.bond_gap_tolerance_m < 0) throw Error(origin + ": slope.bond_gap_tolerance_m must be >= 0");
  if (!g.contains("bedrock") || !g.at("bedrock").is_object())
    throw Error(origin + ": slope.bedrock: missing (the bedrock's surface, radii, porosity and density)");
  const nlohmann::json& bed = g.at("bedrock");
  geo.bedrock = read_part(scene, parameters, bed, "slope.bedrock", {"surface"});
  geo.bedrock.name = "bedrock";
  if (!bed.contains("surface")) throw Error(origin + ": slope.bedrock.surface: missing (points [x_m, y_m] from x = 0 to width_m)");
  geo.bedrock_surface = read_profile(bed.at("surface"), origin + ": slope.bedrock.surface");
  if (g.contains("zones")) {
    const nlohmann::json& zones = g.at("zones");
    if (!zones.is_array()) throw Error(origin + ": slope.zones: must be a list of zones");
    std::set<std::string> names = {"bedrock"};
    for (std::size_t z = 0; z < zones.size(); ++z) {
      const std::string where = "slope.zones[" + std::to_string(z) + "]";
      const nlohmann::json& o = zones[z];
      if (!o.is_object()) throw Error(origin + ": " + where + ": must be an object");
      SlopeZone zone;
      zone.part = read_part(scene, parameters, o, where, {"name", "top"});
      if (!o.contains("name") || !o.at("name").is_string() || o.at("name").get<std::string>().empty())
        throw Error(origin + ": " + where + ".name: missing (a name for the zone's results)");
      zone.part.name = o.at("name").get<std::string>();
      if (!names.insert(zone.part.name).second)
        throw Error(origin + ": " + where + ".name: \"" + zone.part.name + "\" is used twice");
      if (!o.contains("top")) throw Error(origin + ": " + where + ".top: missing (the zone's top profile)");
      zone.top = read_profile(o.at("top"), origin + ": " + where + ".top");
      geo.zones.push_back(std::move(zone));
    }
  }
  geo.validate(origin + ": slope");

  // Boundaries on the three sides that had walls; the top is the free surface.
  const nlohmann::json& b = scene.section("boundaries");
  require_known_fields(b, {"bottom", "left", "right", "top", "note"}, origin + ": boundaries");
  if (b.contains("top"))
    throw Error(origin + ": boundaries.top: a slope's top is its free surface; boundaries go on the bottom, left and "
                "right edges, where the walls stood");
  int inputs = 0;
  for (std::size_t side = 0; side < 3; ++side) {
    if (!b.contains(kSideNames[side]))
      throw Error(origin + ": boundaries." + kSideNames[side] + ": missing (every edge the walls held needs a boundary)");
    s.sides[side] = read_boundary_side(scene, parameters, b.at(kSideNames[side]), std::string("boundaries.") + kSideNames[side]);
    if (s.sides[side].carries_input()) {
      s.input_side = side;
      ++inputs;
    }
  }
  if (inputs != 1)
    throw Error(origin + ": boundaries: exactly one edge must be of type \"input\" or \"velocity\" (the wave's way in), found " +
                std::to_string(inputs));

  const nlohmann::json& m = scene.section("medium");
  s.medium = MediumSpec::read(scene, parameters, m, "medium", {"zones"});
  if (m.contains("zones")) {
    const nlohmann::json& zm = m.at("zones");
    if (!zm.is_object()) throw Error(origin + ": medium.zones: must map zone names to their continuum");
    for (const auto& [name, value] : zm.items()) {
      const bool known = std::any_of(geo.zones.begin(), geo.zones.end(), [&](const SlopeZone& z) { return z.part.name == name; });
      if (!known) throw Error(origin + ": medium.zones." + name + ": no zone of that name in slope.zones");
      s.zone_medium[name] = MediumSpec::read(scene, parameters, value, "medium.zones." + name);
    }
  }
  s.earthquake_input = scene.has_section("earthquake");
  if (s.earthquake_input && scene.has_section("pulse"))
    throw Error(origin + ": pulse and earthquake: give one input, not both (\"pulse\": null removes an inherited pulse)");
  if (s.earthquake_input) s.earthquake = read_earthquake(scene, parameters);
  else s.pulse = PulseSpec::read(scene, parameters, scene.section("pulse"), "pulse");

  const nlohmann::json& mo = scene.section("monitors");
  require_known_fields(mo, {"points", "objective", "radius_m", "note"}, origin + ": monitors");
  if (!mo.contains("points") || !mo.at("points").is_array() || mo.at("points").empty())
    throw Error(origin + ": monitors.points: missing (a list of {\"label\", \"x_m\", \"y_m\"})");
  std::set<std::string> labels;
  for (std::size_t k = 0; k < mo.at("points").size(); ++k) {
    const std::string where = "monitors.points[" + std::to_string(k) + "]";
    const nlohmann::json& p = mo.at("points")[k];
    if (!p.is_object() || !p.contains("label") || !p.at("label").is_string())
      throw Error(origin + ": " + where + ": must be {\"label\", \"x_m\", \"y_m\"}");
    require_known_fields(p, {"label", "x_m", "y_m", "note"}, origin + ": " + where);
    SlopeMonitorSpec point;
    point.label = p.at("label").get<std::string>();
    const bool plain = !point.label.empty() && std::all_of(point.label.begin(), point.label.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
    });
    if (!plain) throw Error(origin + ": " + where + ".label: \"" + point.label + "\" (letters, digits, '-' and '_' only)");
    if (!labels.insert(slope_output_label(point.label)).second)
      throw Error(origin + ": " + where + ".label: \"" + point.label + "\" is used twice");
    number(where, p, "x_m", point.x_m, true);
    number(where, p, "y_m", point.y_m, true);
    if (!(point.x_m >= 0 && point.x_m <= geo.width_m && point.y_m >= 0 && point.y_m <= geo.surface_at(point.x_m)))
      throw Error(origin + ": " + where + ": (" + format_double(point.x_m) + ", " + format_double(point.y_m) +
                  " m) lies outside the model (x from 0 to " + format_double(geo.width_m) + " m, y from 0 to the surface, " +
                  format_double(geo.surface_at(std::clamp(point.x_m, 0.0, geo.width_m))) + " m there)");
    s.monitors.push_back(point);
  }
  if (mo.contains("objective")) {
    if (!mo.at("objective").is_array()) throw Error(origin + ": monitors.objective: must be a list of point labels");
    for (const nlohmann::json& l : mo.at("objective")) {
      if (!l.is_string()) throw Error(origin + ": monitors.objective: must be a list of point labels");
      const std::string label = l.get<std::string>();
      const bool known = std::any_of(s.monitors.begin(), s.monitors.end(), [&](const SlopeMonitorSpec& p) { return p.label == label; });
      if (!known) throw Error(origin + ": monitors.objective: \"" + label + "\" is not a label of monitors.points");
      s.objective.push_back(label);
    }
  }
  number("monitors", mo, "radius_m", s.monitor_radius_m, false);
  if (s.monitor_radius_m < 0) throw Error(origin + ": monitors.radius_m must be >= 0");

  const nlohmann::json& r = scene.section("run");
  require_known_fields(r, {"duration_s", "gravity_m_s2", "record_every_s", "recovery_fraction", "recovery_speed_m_s",
                           "quiet_time_s", "equilibrium_ratio", "max_equilibrium_steps", "equilibrium_damping",
                           "local_damping", "max_wall_s", "max_speed_m_s", "stop_force_ratio", "checkpoint_every_s", "note"},
                       origin + ": run");
  number("run", r, "duration_s", s.duration_s, false);
  number("run", r, "gravity_m_s2", s.gravity_m_s2, false);
  number("run", r, "record_every_s", s.record_every_s, false);
  number("run", r, "recovery_fraction", s.recovery_fraction, false);
  number("run", r, "recovery_speed_m_s", s.recovery_speed_m_s, false);
  number("run", r, "quiet_time_s", s.quiet_time_s, false);
  number("run", r, "equilibrium_ratio", s.equilibrium_ratio, false);
  number("run", r, "max_equilibrium_steps", s.max_equilibrium_steps, false);
  number("run", r, "equilibrium_damping", s.equilibrium_damping, false);
  number("run", r, "local_damping", s.local_damping, false);
  number("run", r, "max_wall_s", s.max_wall_s, false);
  number("run", r, "max_speed_m_s", s.max_speed_m_s, false);
  number("run", r, "stop_force_ratio", s.stop_force_ratio, false);
  number("run", r, "checkpoint_every_s", s.checkpoint_every_s, false);
  const std::string rw = origin + ": run";
  if (!s.earthquake_input && !(s.duration_s > s.pulse.period_s)) throw Error(rw + ".duration_s must exceed pulse.period_s");
  if (!(s.gravity_m_s2 > 0)) throw Error(rw + ".gravity_m_s2 must be positive (the slope rests under gravity)");
  if (!s.earthquake_input && !(s.record_every_s > 0 && s.record_every_s < s.pulse.period_s))
    throw Error(rw + ".record_every_s must lie in (0, pulse.period_s)");
  if (!(s.record_every_s > 0)) throw Error(rw + ".record_every_s must be positive");
  if (s.earthquake_input && !(s.duration_s > s.earthquake.motion.duration_s()))
    throw Error(rw + ".duration_s " + format_double(s.duration_s) + " s must exceed the earthquake's " +
                format_double(s.earthquake.motion.duration_s()) + " s");
  if (!(s.checkpoint_every_s >= 0)) throw Error(rw + ".checkpoint_every_s must be >= 0 (0: no checkpoints)");
  if (!(s.stop_force_ratio >= 0 && s.stop_force_ratio < 1))
    throw Error(rw + ".stop_force_ratio must lie in [0, 1) (0: run to run.duration_s)");
  if (!(s.recovery_fraction > 0 && s.recovery_fraction < 1)) throw Error(rw + ".recovery_fraction must lie in (0, 1)");
  if (!(s.recovery_speed_m_s >= 0)) throw Error(rw + ".recovery_speed_m_s must be >= 0 (0: use recovery_fraction)");
  if (!(s.quiet_time_s >= 0)) throw Error(rw + ".quiet_time_s must be >= 0");
  if (!(s.equilibrium_ratio > 0 && s.equilibrium_ratio < 1)) throw Error(rw + ".equilibrium_ratio must lie in (0, 1)");
  if (!(s.max_equilibrium_steps >= 50)) throw Error(rw + ".max_equilibrium_steps must be at least 50");
  if (!(s.equilibrium_damping >= 0 && s.equilibrium_damping < 1)) throw Error(rw + ".equilibrium_damping must lie in [0, 1)");
  if (!(s.local_damping >= 0 && s.local_damping < 1)) throw Error(rw + ".local_damping must lie in [0, 1)");
  if (!(s.max_wall_s > 0)) throw Error(rw + ".max_wall_s must be positive");
  if (!(s.max_speed_m_s > 0)) throw Error(rw + ".max_speed_m_s must be positive");
  return s;
}

TestResult run_slope(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const SlopeTestSpec s = SlopeTestSpec::from_scene(scene, parameters);
  const std::string& origin = scene.origin();
  SlopeSpec geometry = s.geometry;
  geometry.seed = options.seed;
  const SlopeSpecimen specimen = build_slope_specimen(geometry, options.cache_dir);
  const double W = specimen.width_m, t = specimen.thickness_m;

  TestResult result;
  for (std::size_t p = 0; p < specimen.part_names.size(); ++p) {
    result.specimen_info["disks_" + specimen.part_names[p]] = static_cast<double>(specimen.part_disks[p]);
    result.specimen_info["area_m2_" + specimen.part_names[p]] = specimen.part_area_m2[p];
  }

  // The world: bedrock and rockfill disks, walls at the packing's bottom, left and right faces.
  WorldSettings settings;
  settings.thickness_m = t;
  settings.damping = s.equilibrium_damping;
  settings.gravity_y_m_s2 = -s.gravity_m_s2;
  apply_run_options(settings, options);
  World world(settings);
  bind_contact_models(world, scene, parameters);
  Bodies& b = world.bodies;
  b.reserve(specimen.size());
  double r_min = INFINITY, r_max = 0;
  for (const std::size_t i : particle_order(specimen.size(), options.particle_order_seed)) {
    const std::uint8_t part = specimen.part[i];
    b.add_disk(specimen.x[i], specimen.y[i], specimen.radius[i], specimen.part_density_kg_m3[part], t,
               part == 0 ? kBedrockGroup : kRockfillGroup, static_cast<std::int64_t>(i));
    r_min = std::min(r_min, specimen.radius[i]);
    r_max = std::max(r_max, specimen.radius[i]);
  }
  result.particles = b.size();
  const double H = specimen.height_m;
  Wall bottom, left, right;
  bottom.x0 = -0.1 * W;
  bottom.x1 = 1.1 * W;
  left.y0 = right.y0 = -0.1 * H;
  left.y1 = right.y1 = 1.1 * H;
  right.x0 = right.x1 = W;
  bottom.group = left.group = right.group = kWallGroup;
  bottom.inward_ny = 1;
  left.inward_nx = 1;
  right.inward_nx = -1;
  world.walls = {bottom, left, right};
  world.make_wall_contacts_force_free();
  const double tolerance = s.bond_gap_tolerance_m > 0 ? s.bond_gap_tolerance_m : 0.01 * r_min;
  result.specimen_info["bonds_installed"] = static_cast<double>(world.install_bonds(tolerance, options.seed));

  // The continuum behind each part's dashpots has the bulk density its boxes were packed to, density (1 - n); the
  // mass over the region it fills says how well the cut filled the region (less where parts meet).
  std::vector<double> part_mass(specimen.part_names.size(), 0.0);
  for (std::size_t i : disks_by_id(b)) part_mass[specimen.part[b.id[i]]] += b.mass[i];
  std::vector<DiskImpedance> part_impedance(specimen.part_names.size());
  std::vector<bool> part_has_medium(specimen.part_names.size(), false);
  for (std::size_t p = 0; p < specimen.part_names.size(); ++p) {
    const double rho = specimen.part_density_kg_m3[p] * (1 - specimen.part_porosity[p]);
    result.specimen_info["bulk_density_kg_m3_" + specimen.part_names[p]] = rho;
    result.specimen_info["fill_density_kg_m3_" + specimen.part_names[p]] = part_mass[p] / (specimen.part_area_m2[p] * t);
    const MediumSpec* medium = &s.medium;
    if (p > 0) {
      const auto found = s.zone_medium.find(specimen.part_names[p]);
      medium = found == s.zone_medium.end() ? nullptr : &found->second;
    }
    if (!medium) continue;
    part_has_medium[p] = true;
    part_impedance[p] = {rho, medium->p_speed_m_s(rho), medium->s_speed_m_s(rho)};
    result.specimen_info["dashpot_wave_speed_p_m_s_" + specimen.part_names[p]] = part_impedance[p].c_p_m_s;
    result.specimen_info["dashpot_wave_speed_s_m_s_" + specimen.part_names[p]] = part_impedance[p].c_s_m_s;
  }

  // At rest under gravity against the walls.
  world.refresh();
  if (!s.earthquake_input && world.dt_s() * 10 > s.pulse.period_s)
    throw Error(origin + ": pulse.period_s " + format_double(s.pulse.period_s) + " s is shorter than 10 time steps (dt " +
                format_double(world.dt_s()) + " s): the pulse would not be resolved");
  result.specimen_info["time_step_s"] = world.dt_s();
  // Each material at rest on its own measure: the rockfill's contacts carry forces a thousand times smaller than
  // the bedrock's, and a ratio over both would call a creeping deposit at rest.
  const bool has_deposit = !geometry.zones.empty();
  auto ratios = [&] {
    return std::array<double, 2>{force_ratio(world, kBedrockGroup), has_deposit ? force_ratio(world, kRockfillGroup) : 0.0};
  };
  // The rest under gravity does not depend on what comes after it (the boundaries' coefficients, the input): a
  // section brought to rest once is kept in the cache and read back by every run that shares it.
  const std::string rest_key = slope_rest_key(scene, parameters, s, options);
  const std::string rest_path = options.cache_dir.empty() ? std::string() : cache_file(options.cache_dir, "slope_rest_", rest_key);
  bool at_rest = !rest_path.empty() && read_rest_state(world, rest_path, rest_key);
  if (!at_rest) {
    for (std::uint64_t done = 0; done < static_cast<std::uint64_t>(s.max_equilibrium_steps) && !at_rest; done += 50) {
      world.run(50);
      const std::array<double, 2> r = ratios();
      at_rest = r[0] < s.equilibrium_ratio && r[1] < s.equilibrium_ratio;
    }
    if (at_rest && !rest_path.empty()) write_rest_state(world, rest_path, rest_key);
  }
  const std::array<double, 2> rest_ratio = ratios();
  result.specimen_info["equilibrium_steps"] = static_cast<double>(world.steps_done());
  result.specimen_info["equilibrium_force_ratio_bedrock"] = rest_ratio[0];
  if (has_deposit) result.specimen_info["equilibrium_force_ratio_rockfill"] = rest_ratio[1];
  if (!at_rest) {
    result.reason = "the slope did not come to rest under gravity within run.max_equilibrium_steps (force ratio " +
                    format_double(rest_ratio[0]) + " in the bedrock" +
                    (has_deposit ? ", " + format_double(rest_ratio[1]) + " in the rockfill" : std::string()) +
                    ", asked below " + format_double(s.equilibrium_ratio) + ")";
    return result;
  }
  result.specimen_info["equilibrium_bonds_broken"] = static_cast<double>(world.breaks().size());

  // The walls become boundaries.
  auto boundary = std::make_unique<BoundaryForces>();
  const auto impedance = [&](std::size_t disk) {
    const std::uint8_t part = specimen.part[b.id[disk]];
    return part_impedance[part];
  };
  for (std::size_t side = 0; side < 3; ++side) {
    const std::string name = SlopeTestSpec::kSideNames[side];
    BoundarySide where;
    where.wall = side;
    where.name = name;
    where.inward = kInward[side];
    where.along_x = side == 0;
    where.to_m = side == 0 ? W : 0.0;  // a side edge: up to its highest disk, wherever the surface settled
    where.near_gap_fraction = kNearWallGap;
    const SideSpec& spec = s.sides[side];
    if (spec.has_dashpots()) {  // every part whose disks meet a dashpot side needs its continuum
      const ContactSet& wp = world.wall_pairs();
      for (std::size_t k = 0; k < wp.size(); ++k) {
        if (static_cast<std::size_t>(wp.j[k]) != side || !(wp.flags[k] & kTouching)) continue;
        const std::uint8_t part = specimen.part[b.id[static_cast<std::size_t>(wp.i[k])]];
        if (!part_has_medium[part])
          throw Error(origin + ": medium.zones." + specimen.part_names[part] + ": missing; the zone's disks touch the " +
                      name + " edge, whose dashpots need its continuum (E_d_Pa and nu_d, or the wave speeds)");
      }
    }
    const BoundarySideSummary summary = install_boundary_side(world, where, spec, impedance, *boundary, origin);
    record_boundary_side(result, name, spec, summary);
    result.specimen_info["boundary_length_m_" + name] = summary.length_m;
  }
  BoundaryForces& forces = world.add_external_forces(std::move(boundary));
  world.settings().damping = s.local_damping;
  world.refresh();

  // A quiet period: the boundaries must hold the slope where the walls did.
  result.macro["quiet_drift_m"] = run_quiet_period(world, s.quiet_time_s);
  result.macro["quiet_force_ratio"] = force_ratio(world, kBedrockGroup);
  if (has_deposit) result.specimen_info["quiet_force_ratio_rockfill"] = force_ratio(world, kRockfillGroup);

  // The deposit's horizontal extent: where 1 % of its disks lie left of (right of) it, so that a few disks a
  // boundary let through (it damps them; it does not hold them like a wall) do not stand for the deposit.
  auto deposit_extent = [&](double& from_m, double& to_m) {
    std::vector<double> x;
    for (std::size_t i : disks_by_id(b))
      if (b.group[i] == kRockfillGroup) x.push_back(b.x[i]);
    std::sort(x.begin(), x.end());
    const std::size_t k = x.size() / 100;
    from_m = x[k];
    to_m = x[x.size() - 1 - k];
  };
  // A disk that has left the section sideways or through the base is taken out of the run: held where it is, at
  // rest. Nothing is left under it to stop its fall, and it would fall without end.
  std::size_t disks_out = 0;
  auto retire_escaped = [&] {
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.fixed[i] || (b.x[i] >= -r_max && b.x[i] <= W + r_max && b.y[i] >= -r_max)) continue;
      b.fixed[i] = 1;
      b.vx[i] = b.vy[i] = b.w[i] = 0;
      ++disks_out;
    }
  };
  if (has_deposit) deposit_extent(result.macro["deposit_left_start_m"], result.macro["deposit_right_start_m"]);

  // Monitors.
  const double radius = s.monitor_radius_m > 0 ? s.monitor_radius_m : 2 * r_max;
  const std::size_t in = s.input_side;
  auto distance_from_input = [&](double x, double y) { return in == 0 ? y : in == 1 ? x : W - x; };
  WaveRecord rec;
  for (const SlopeMonitorSpec& p : s.monitors) {
    Monitor m;
    m.label = slope_output_label(p.label);
    m.x_m = p.x_m;
    m.y_m = p.y_m;
    m.distance_m = distance_from_input(p.x_m, p.y_m);
    // The point's own material: the group of the disk nearest it (a point in the bedrock near the surface does not
    // average the rockfill's motion in).
    std::size_t nearest_disk = 0;
    double nearest_m = INFINITY;
    for (std::size_t i : disks_by_id(b)) {
      const double d = std::hypot(b.x[i] - p.x_m, b.y[i] - p.y_m) - b.radius[i];
      if (d < nearest_m) {
        nearest_m = d;
        nearest_disk = i;
      }
    }
    m.collect(b, radius, origin, b.group[nearest_disk]);
    rec.monitors.push_back(std::move(m));
  }

  // The wave, from t = 0 of the test: P along the input edge's inward normal, S along the edge, a positive S
  // towards +x on the bottom edge and +y on the side edges (the boundary's tangent turns 90 degrees anticlockwise
  // from the inward normal: -x on the bottom, +y on the left, -y on the right).
  world.start_test();
  const double s_sign = in == 1 ? 1.0 : -1.0;
  double input_end_s = 0, input_peak_m_s = 0;
  if (s.earthquake_input) {
    const EarthquakeSpec& q = s.earthquake;
    const GroundMotion& motion = q.motion;
    input_end_s = motion.duration_s();
    input_peak_m_s = motion.peak_speed_m_s();
    result.specimen_info["input_peak_acceleration_m_s2"] = motion.peak_acceleration_m_s2();
    result.specimen_info["input_baseline_offset_m_s2"] = motion.baseline_offset_m_s2;
    result.specimen_info["input_duration_s"] = input_end_s;
    if (q.s_wave)
      forces.set_input(nullptr, [motion, s_sign](double time) { return s_sign * motion.velocity_at(time); });
    else
      forces.set_input([motion](double time) { return motion.velocity_at(time); }, nullptr);
  } else {
    const PulseSpec pulse = s.pulse;
    input_end_s = pulse.period_s;
    input_peak_m_s = std::hypot(pulse.p_amplitude_m_s, pulse.s_amplitude_m_s);
    forces.set_input([pulse](double time) { return PulseSpec::cosine(pulse.p_amplitude_m_s, pulse.period_s, time); },
                     [pulse, s_sign](double time) {
                       return s_sign * PulseSpec::cosine(pulse.s_amplitude_m_s, pulse.period_s, time);
                     });
  }
  result.macro["input_peak_speed_m_s"] = input_peak_m_s;
  const double absorbed_before = forces.dashpot_work_j();
  // Snapshots for ParaView (--vtk): at rest before the wave, when the input ends, and at the end.
  auto snapshot_at = [&](const char* name) {
    if (options.vtk_dir.empty()) return;
    std::filesystem::create_directories(options.vtk_dir);
    write_vtk_disks(world, options.vtk_dir + "/slope_" + name + ".vtk");
  };
  snapshot_at("start");
  bool input_snapshot_done = false;
  // A checkpoint of this very run (everything that sets its numbers, not the limits it gives up at), written every
  // run.checkpoint_every_s and read back by a run that finds it; the neighbour list is rebuilt at each one on both
  // paths, so the resumed run has the bits of the one that went through.
  const std::string checkpoint_key = rest_key + "|" + wave_run_key(scene, parameters);
  const std::string checkpoint_path = s.checkpoint_every_s > 0 && !options.cache_dir.empty()
                                          ? cache_file(options.cache_dir, "slope_run_", checkpoint_key)
                                          : std::string();
  WaveRunState state{world, forces, rec, disks_out, input_snapshot_done};
  const bool resumed = !checkpoint_path.empty() && read_wave_checkpoint(checkpoint_path, checkpoint_key, state);
  if (resumed) log::info("slope: resuming from the checkpoint at t = " + format_double(world.time_s()) + " s (" + checkpoint_path + ")");
  double next_checkpoint_s = s.checkpoint_every_s > 0 ? (std::floor(world.time_s() / s.checkpoint_every_s) + 1) * s.checkpoint_every_s : INFINITY;
  const auto loading_start = std::chrono::steady_clock::now();
  RecordedRun run;
  run.end_time_s = s.duration_s;
  run.steps_per_record = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(s.record_every_s / world.dt_s())));
  run.max_speed_m_s = s.max_speed_m_s;
  run.max_speed_reason = "run.max_speed_m_s (" + format_double(s.max_speed_m_s) + " m/s)";
  run.max_wall_s = s.max_wall_s;
  run.start = start;
  run.progress_label = "slope (% of run.duration_s)";
  run.show_progress = options.progress;
  run.record_first = !resumed;
  run.done = [&] {
    retire_escaped();
    if (!input_snapshot_done && world.time_s() >= input_end_s) {
      snapshot_at("input_end");
      input_snapshot_done = true;
    }
    if (world.time_s() >= next_checkpoint_s) {
      if (!checkpoint_path.empty()) write_wave_checkpoint(checkpoint_path, checkpoint_key, state);
      world.refresh();  // on both paths, so a resumed run steps on from the same neighbour list and time step
      next_checkpoint_s += s.checkpoint_every_s;
    }
    if (!(s.stop_force_ratio > 0) || world.time_s() < input_end_s) return false;
    const std::array<double, 2> r = ratios();
    return r[0] < s.stop_force_ratio && r[1] < s.stop_force_ratio;
  };
  run_recording(world, rec, run, result);
  if (result.ok && !checkpoint_path.empty()) std::filesystem::remove(checkpoint_path);  // done: nothing to resume
  snapshot_at("end");
  result.macro["end_time_s"] = world.time_s();
  const std::array<double, 2> end_ratio = ratios();
  result.macro["end_force_ratio"] = std::max(end_ratio[0], end_ratio[1]);
  result.macro["disks_out_of_section"] = static_cast<double>(disks_out);
  record_run_timing(world, options, start, loading_start, result);
  rec.add_series(result);
  if (!result.ok) return result;

  // Recovery: below run.recovery_speed_m_s, or a share of the peak the slope carried at the point nearest the input.
  std::size_t nearest = 0;
  for (std::size_t k = 1; k < rec.monitors.size(); ++k)
    if (rec.monitors[k].distance_m < rec.monitors[nearest].distance_m) nearest = k;
  const std::vector<double> nearest_speed = rec.monitors[nearest].speeds();
  const double carried = *std::max_element(nearest_speed.begin(), nearest_speed.end());
  result.specimen_info["carried_peak_speed_m_s"] = carried;
  const double threshold = s.recovery_speed_m_s > 0 ? s.recovery_speed_m_s : s.recovery_fraction * carried;
  result.specimen_info["recovery_threshold_m_s"] = threshold;
  double total = 0;
  for (const Monitor& m : rec.monitors) {
    const std::vector<double> speed = m.speeds();
    const Recovery r = recovery_time(rec.times, speed, threshold);
    result.macro["recovery_time_s_" + m.label] = r.time_s;
    result.macro["recovered_" + m.label] = r.recovered ? 1.0 : 0.0;
    const std::size_t peak = static_cast<std::size_t>(std::max_element(speed.begin(), speed.end()) - speed.begin());
    result.macro["peak_speed_m_s_" + m.label] = speed[peak];
    result.macro["peak_time_s_" + m.label] = rec.times[peak];
    const bool counted = s.objective.empty() ||
                         std::any_of(s.objective.begin(), s.objective.end(),
                                     [&](const std::string& l) { return slope_output_label(l) == m.label; });
    if (counted) total += r.time_s;
  }
  result.macro["total_recovery_time_s"] = total;
  if (has_deposit) deposit_extent(result.macro["deposit_left_end_m"], result.macro["deposit_right_end_m"]);
  result.macro["energy_input_J"] = forces.input_work_j();
  result.macro["energy_absorbed_J"] = -(forces.dashpot_work_j() - absorbed_before);
  result.macro["kinetic_energy_end_J"] = world.kinetic_energy();
  result.macro["bonds_broken"] = static_cast<double>(world.breaks().size());
  return result;
}

namespace {

class SlopeTest : public LabTest {
 public:
  std::string name() const override { return "slope"; }
  std::string description() const override {
    return "slope: a bedrock and rockfill section at rest under gravity, viscous and input boundaries on its edges, a "
           "wave in through the input edge; recovery times, peaks, the deposit's extent";
  }
  int dimension() const override { return 2; }
  const ContactModelCatalog& contact_models() const override { return disk_contact_models(); }
  std::vector<BoundaryRole> boundary_roles() const override {
    return {{"particle-wall", kWallGroup, "every disk against the walls on the bottom, left and right, until the boundaries replace them"}};
  }
  std::vector<SceneSection> sections() const override {
    return {{"slope", "the section: size, the bedrock's surface and disks, the rockfill zones on it", true, true},
            {"boundaries", "the bottom, left and right edges' types (fixed, free, viscous, input, velocity) and dashpot coefficients", false, true},
            {"medium", "the continuum behind the dashpots: the bedrock's E_d, nu_d (or wave speeds), and each zone's", false, true},
            {"pulse", "the cosine pulse's amplitudes (P, S) and period", false, false},
            {"earthquake", "an acceleration record sent in instead of the pulse: file, format, units, scale, duration, wave, baseline", false, false},
            {"monitors", "monitoring points in metres, and those whose recovery times make the objective", false, true},
            {"run", "duration, gravity, recording, recovery threshold, rest and quiet period, damping", false, false}};
  }
  std::vector<ContactRole> specimen_roles(const Scene&) const override {
    return {{"bedrock-bedrock", {{kBedrockGroup, kBedrockGroup}}, "the bedrock's disks against each other"},
            {"rockfill-rockfill", {{kRockfillGroup, kRockfillGroup}}, "the rockfill zones' disks against each other"},
            {"rockfill-bedrock", {{kRockfillGroup, kBedrockGroup}}, "the rockfill resting on the bedrock"}};
  }
  bool exact_scaling() const override { return false; }  // a dynamic test: inertia and gravity set its numbers
  void check_scene(const Scene& scene) const override { SlopeTestSpec::from_scene(scene, scene.resolve({})); }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"total_recovery_time_s"}; }
  std::pair<std::string, std::string> curve_axes() const override { return {"", ""}; }  // velocity histories
  std::vector<OutputSpec> outputs(const Scene& scene) const override {
    std::vector<OutputSpec> out;
    SlopeTestSpec spec;
    try {
      spec = SlopeTestSpec::from_scene(scene, scene.resolve({}));
    } catch (const Error&) {
    }
    for (const SlopeMonitorSpec& p : spec.monitors) {
      const std::string l = slope_output_label(p.label);
      add_recovery_outputs(out, l, "the recovery threshold");
      out.push_back({"peak_speed_m_s_" + l, "m/s", "largest speed recorded at " + p.label, true, kNonNegative});
      out.push_back({"peak_time_s_" + l, "s", "when it was recorded", true, kNonNegative});
    }
    out.push_back({"total_recovery_time_s", "s",
                   "sum of the recovery times of the points in monitors.objective (all points when it is absent): Ma et "
                   "al. 2022's fitness", true, kNonNegative});
    const bool deposit = !spec.geometry.zones.empty();
    for (const char* when : {"start", "end"}) {
      out.push_back({std::string("deposit_left_") + when + "_m", "m",
                     std::string("the rockfill's left end at the ") + when + " of the wave run: 1 % of its disk centres lie "
                     "left of it", deposit, kAnyValue});
      out.push_back({std::string("deposit_right_") + when + "_m", "m",
                     std::string("the rockfill's right end at the ") + when + " of the wave run: 1 % of its disk centres "
                     "lie right of it", deposit, kAnyValue});
    }
    out.push_back({"input_peak_speed_m_s", "m/s", "largest speed of the input wave's particle velocity (of the record "
                   "after its baseline correction, or the pulse's P and S together)", true, kNonNegative});
    out.push_back({"end_time_s", "s", "simulated time when the run ended (run.duration_s, or earlier by run.stop_force_ratio)",
                   true, kNonNegative});
    out.push_back({"end_force_ratio", "1", "the larger of the bedrock's and the rockfill's mean unbalanced-force ratio at the end",
                   true, kNonNegative});
    out.push_back({"disks_out_of_section", "1", "disks whose centre left the section (more than the largest radius "
                   "beyond its left, right or bottom edge) and were held there: a viscous boundary damps the disks "
                   "crossing it, it does not hold them", true, kNonNegative});
    add_energy_outputs(out);
    out.push_back({"bonds_broken", "1", "bonds broken since the wave started", true, kNonNegative});
    add_quiet_outputs(out, "the bedrock's");
    return out;
  }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_slope(scene, parameters, options);
  }
};

}  // namespace

void register_slope_test(LabTestRegistry& registry) { registry.add(std::make_unique<SlopeTest>()); }

}  // namespace demcal::dem
