// Wave-strip test: the walls of a bonded strip at rest under gravity become
// boundaries (fixed, free, viscous, input or velocity), a cosine pulse enters through
// the input side, and monitoring points record how the strip rings and falls
// quiet (wave_strip_test.hpp).
#include "demcal/dem/wave_strip_test.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/boundary_forces.hpp"
#include "demcal/dem/equilibrium.hpp"
#include "demcal/dem/builtin_tests.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/wave_signals.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

// Inward unit normal of each side (bottom, top, left, right).
constexpr std::array<std::array<double, 2>, 4> kInward = {{{0, 1}, {0, -1}, {1, 0}, {-1, 0}}};

std::array<double, 2> fraction_pair(const nlohmann::json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw Error(where + ": must be [x / width, y / height]");
  const std::array<double, 2> p = {v[0].get<double>(), v[1].get<double>()};
  if (!(p[0] >= 0 && p[0] <= 1 && p[1] >= 0 && p[1] <= 1))
    throw Error(where + ": [" + format_double(p[0]) + ", " + format_double(p[1]) +
                "] lies outside the model (fractions of its width and height, each in [0, 1])");
  return p;
}

}  // namespace

WaveStripSpec WaveStripSpec::from_scene(const Scene& scene, const std::map<std::string, double>& parameters) {
  const std::string& origin = scene.origin();
  WaveStripSpec s;
  auto number = [&](const std::string& section, const nlohmann::json& object, const char* key, double& target,
                    bool required) { read_section_number(scene, parameters, section, object, key, target, required); };

  const nlohmann::json& b = scene.section("boundaries");
  require_known_fields(b, {"bottom", "top", "left", "right", "note"}, origin + ": boundaries");
  int inputs = 0;
  for (std::size_t side = 0; side < 4; ++side) {
    const std::string where = std::string("boundaries.") + kSideNames[side];
    if (!b.contains(kSideNames[side])) continue;
    s.sides[side] = read_boundary_side(scene, parameters, b.at(kSideNames[side]), where);
    if (s.sides[side].carries_input()) {
      s.input_side = side;
      ++inputs;
    }
  }
  if (inputs != 1)
    throw Error(origin + ": boundaries: exactly one side must be of type \"input\" or \"velocity\" (the pulse's way in), found " +
                std::to_string(inputs));

  s.medium = MediumSpec::read(scene, parameters, scene.section("medium"), "medium");
  s.pulse = PulseSpec::read(scene, parameters, scene.section("pulse"), "pulse");

  const nlohmann::json& mo = scene.section("monitors");
  require_known_fields(mo, {"points", "reflection_point", "radius_m", "note"}, origin + ": monitors");
  if (!mo.contains("points") || !mo.at("points").is_array() || mo.at("points").empty())
    throw Error(origin + ": monitors.points: missing (a list of [x / width, y / height], the points T1, T2, ...)");
  for (std::size_t k = 0; k < mo.at("points").size(); ++k)
    s.points.push_back(fraction_pair(mo.at("points")[k], origin + ": monitors.points[" + std::to_string(k) + "]"));
  if (mo.contains("reflection_point"))
    s.reflection_point = fraction_pair(mo.at("reflection_point"), origin + ": monitors.reflection_point");
  number("monitors", mo, "radius_m", s.monitor_radius_m, false);
  if (s.monitor_radius_m < 0) throw Error(origin + ": monitors.radius_m must be >= 0");

  const nlohmann::json& r = scene.section("run");
  require_known_fields(r, {"duration_s", "gravity_m_s2", "record_every_s", "recovery_fraction", "quiet_time_s",
                           "equilibrium_ratio", "max_equilibrium_steps", "local_damping", "max_wall_s", "note"},
                       origin + ": run");
  number("run", r, "duration_s", s.duration_s, false);
  number("run", r, "gravity_m_s2", s.gravity_m_s2, false);
  number("run", r, "record_every_s", s.record_every_s, false);
  number("run", r, "recovery_fraction", s.recovery_fraction, false);
  number("run", r, "quiet_time_s", s.quiet_time_s, false);
  number("run", r, "equilibrium_ratio", s.equilibrium_ratio, false);
  number("run", r, "max_equilibrium_steps", s.max_equilibrium_steps, false);
  number("run", r, "local_damping", s.local_damping, false);
  number("run", r, "max_wall_s", s.max_wall_s, false);
  const std::string rw = origin + ": run";
  if (!(s.duration_s > s.pulse.period_s)) throw Error(rw + ".duration_s must exceed pulse.period_s");
  if (!(s.gravity_m_s2 >= 0)) throw Error(rw + ".gravity_m_s2 must be >= 0 (it acts downwards)");
  if (!(s.record_every_s > 0 && s.record_every_s < s.pulse.period_s))
    throw Error(rw + ".record_every_s must lie in (0, pulse.period_s)");
  if (!(s.recovery_fraction > 0 && s.recovery_fraction < 1)) throw Error(rw + ".recovery_fraction must lie in (0, 1)");
  if (!(s.quiet_time_s >= 0)) throw Error(rw + ".quiet_time_s must be >= 0");
  if (!(s.equilibrium_ratio > 0 && s.equilibrium_ratio < 1)) throw Error(rw + ".equilibrium_ratio must lie in (0, 1)");
  if (!(s.max_equilibrium_steps >= 50)) throw Error(rw + ".max_equilibrium_steps must be at least 50");
  if (!(s.local_damping >= 0 && s.local_damping < 1)) throw Error(rw + ".local_damping must lie in [0, 1)");
  if (!(s.max_wall_s > 0)) throw Error(rw + ".max_wall_s must be positive");
  return s;
}

TestResult run_wave_strip(const Scene& scene, const std::map<std::string, double>& parameters,
                          const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const WaveStripSpec s = WaveStripSpec::from_scene(scene, parameters);
  const std::string& origin = scene.origin();
  Specimen specimen = cached_specimen(specimen_spec(scene, parameters, options.seed), options.cache_dir);
  const double W = specimen.width_m, H = specimen.height_m;

  TestResult result;
  World world = make_platen_world(scene, parameters, specimen, options.seed, nullptr, &result.specimen_info, true, nullptr,
                                  &options);
  for (Wall& w : world.walls) w.vx = w.vy = 0;  // the vessel holds still
  Bodies& b = world.bodies;
  result.particles = b.size();
  const double r_max = *std::max_element(b.radius.begin(), b.radius.end());
  const double t = specimen.thickness_m;
  double mass = 0;
  for (std::size_t i : disks_by_id(b)) mass += b.mass[i];
  const double rho = mass / (W * H * t);  // the equivalent continuum's (bulk) density
  const double c_p = s.medium.p_speed_m_s(rho), c_s = s.medium.s_speed_m_s(rho);
  result.specimen_info["bulk_density_kg_m3"] = rho;
  result.specimen_info["dashpot_wave_speed_p_m_s"] = c_p;
  result.specimen_info["dashpot_wave_speed_s_m_s"] = c_s;
  if (s.medium.e_d_pa > 0) {
    result.specimen_info["formula_wave_speed_p_m_s"] = s.medium.p_speed_formula_m_s(rho);
    result.specimen_info["formula_wave_speed_s_m_s"] = s.medium.s_speed_formula_m_s(rho);
    // Both P formulas, whichever the dashpots use: Ma et al.'s (plane strain, which their coefficients are
    // relative to) and the 2D disk assembly's own (plane stress), 4 % slower at nu 0.22.
    result.specimen_info["ma2022_wave_speed_p_m_s"] = s.medium.p_speed_ma2022_m_s(rho);
    result.specimen_info["plane_stress_wave_speed_p_m_s"] = s.medium.p_speed_plane_stress_m_s(rho);
  }

  // At rest under gravity against the vessel's walls.
  world.settings().damping = scene.loading().local_damping;
  world.settings().gravity_y_m_s2 = -s.gravity_m_s2;
  world.refresh();
  if (world.dt_s() * 10 > s.pulse.period_s)
    throw Error(origin + ": pulse.period_s " + format_double(s.pulse.period_s) + " s is shorter than 10 time steps (dt " +
                format_double(world.dt_s()) + " s): the pulse would not be resolved");
  if (s.gravity_m_s2 > 0 &&
      !cycle_to_equilibrium(world, s.equilibrium_ratio, static_cast<std::uint64_t>(s.max_equilibrium_steps))) {
    result.reason = "the strip did not come to rest under gravity within run.max_equilibrium_steps (force ratio " +
                    format_double(force_ratio(world)) + ", asked below " + format_double(s.equilibrium_ratio) + ")";
    return result;
  }
  result.specimen_info["equilibrium_steps"] = static_cast<double>(world.steps_done());
  result.specimen_info["equilibrium_force_ratio"] = force_ratio(world);

  // The walls' load passes to their disks; fixed sides hold theirs.
  auto boundary = std::make_unique<BoundaryForces>();
  const auto impedance = [&](std::size_t) { return DiskImpedance{rho, c_p, c_s}; };
  for (std::size_t side = 0; side < 4; ++side) {
    const std::string name = WaveStripSpec::kSideNames[side];
    BoundarySide where;
    where.wall = side;
    where.name = name;
    where.inward = kInward[side];
    where.along_x = side < 2;
    where.to_m = side < 2 ? W : H;
    const SideSpec& spec = s.sides[side];
    record_boundary_side(result, name, spec, install_boundary_side(world, where, spec, impedance, *boundary, origin));
  }
  BoundaryForces& forces = world.add_external_forces(std::move(boundary));
  world.settings().damping = s.local_damping;
  world.refresh();

  // A quiet period: the boundaries must hold the strip where the walls did.
  result.macro["quiet_drift_m"] = run_quiet_period(world, s.quiet_time_s);
  result.macro["quiet_force_ratio"] = force_ratio(world);
  double quiet_speed = 0;
  for (std::size_t i = 0; i < b.size(); ++i) quiet_speed = std::max(quiet_speed, std::hypot(b.vx[i], b.vy[i]));
  result.specimen_info["quiet_max_speed_m_s"] = quiet_speed;

  // Monitors: the disks within the radius of each point.
  const double radius = s.monitor_radius_m > 0 ? s.monitor_radius_m : 2 * r_max;
  const std::size_t in = s.input_side;
  const double length_m = in < 2 ? H : W;  // the pulse's path, from the input face to the opposite one
  auto distance_from_input = [&](double x, double y) {
    switch (in) {
      case 0: return y;
      case 1: return H - y;
      case 2: return x;
      default: return W - x;
    }
  };
  WaveRecord rec;
  std::vector<Monitor>& monitors = rec.monitors;
  for (std::size_t k = 0; k <= s.points.size(); ++k) {
    const bool reflection = k == s.points.size();
    const std::array<double, 2> f = reflection ? s.reflection_point : s.points[k];
    Monitor m;
    m.label = reflection ? "R" : "T" + std::to_string(k + 1);
    m.x_m = f[0] * W;
    m.y_m = f[1] * H;
    m.distance_m = distance_from_input(m.x_m, m.y_m);
    m.collect(b, radius, origin);
    monitors.push_back(std::move(m));
  }

  // The pulse, from t = 0 of the test.
  world.start_test();
  const double period = s.pulse.period_s, a_p = s.pulse.p_amplitude_m_s, a_s = s.pulse.s_amplitude_m_s;
  auto cosine = [period](double amplitude, double time) {
    return time <= period ? 0.5 * amplitude * (1 - std::cos(2 * M_PI * time / period)) : 0.0;
  };
  forces.set_input([=](double time) { return cosine(a_p, time); }, [=](double time) { return cosine(a_s, time); });
  const double work_before_input = forces.applied_work_j(), absorbed_before = forces.dashpot_work_j();
  const std::vector<double> x_start = b.x, y_start = b.y;

  const auto loading_start = std::chrono::steady_clock::now();
  const auto steps_per_record =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(s.record_every_s / world.dt_s())));
  RecordedRun run;
  run.end_time_s = s.duration_s;
  run.steps_per_record = steps_per_record;
  run.max_speed_m_s = 100 * std::max(a_p, a_s);
  run.max_speed_reason = "100 x the pulse's amplitude";
  run.max_wall_s = s.max_wall_s;
  run.start = start;
  run.progress_label = "wave strip (% of run.duration_s)";
  run.show_progress = options.progress;
  run_recording(world, rec, run, result);
  record_run_timing(world, options, start, loading_start, result);
  rec.add_series(result);  // time, the kinetic energy, each point's velocity
  if (!result.ok) return result;

  // Velocity along the pulse's path (P) and across it (S), per point.
  const double nx = kInward[in][0], ny = kInward[in][1], tx = -ny, ty = nx;
  auto along = [&](const Monitor& m, bool p_wave) {
    std::vector<double> v(m.vx.size());
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = p_wave ? m.vx[k] * nx + m.vy[k] * ny : m.vx[k] * tx + m.vy[k] * ty;
    return v;
  };
  // Quiet means below a share of the pulse the strip actually carried (the peak speed at the point nearest the
  // input), not of A: an input side's dashpots set how much of A enters (2 xi / (1 + xi) of it for a matched
  // strip), and a threshold on A would reward a weak input side with early quiet.
  std::vector<std::vector<double>> speeds;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    speeds.push_back(monitors[k].speeds());
  }
  std::size_t nearest_input = 0;
  for (std::size_t k = 1; k < s.points.size(); ++k)
    if (monitors[k].distance_m < monitors[nearest_input].distance_m) nearest_input = k;
  const double carried = *std::max_element(speeds[nearest_input].begin(), speeds[nearest_input].end());
  result.specimen_info["carried_peak_speed_m_s"] = carried;
  double total = 0;
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const Monitor& m = monitors[k];
    const Recovery r = recovery_time(rec.times, speeds[k], s.recovery_fraction * carried);
    result.macro["recovery_time_s_" + m.label] = r.time_s;
    result.macro["recovered_" + m.label] = r.recovered ? 1.0 : 0.0;
    total += r.time_s;
  }
  result.macro["total_recovery_time_s"] = total;

  // Wave speeds from the arrivals (the first rise through half the pulse's
  // peak at the point nearest the input), over the points T1, T2, ...
  auto speed_of = [&](bool p_wave) {
    const std::vector<double> first = along(monitors[nearest_input], p_wave);
    const double level = 0.5 * *std::max_element(first.begin(), first.end());
    std::vector<double> distance, arrival;
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      distance.push_back(monitors[k].distance_m);
      arrival.push_back(first_crossing(rec.times, along(monitors[k], p_wave), level));
    }
    return arrival_speed(distance, arrival);
  };
  // Each wave's speed when the pulse has that wave; the reflection is the P wave's (the S wave's for an S pulse).
  const bool p_wave = a_p > 0;
  double measured = 0;
  for (bool p : {true, false}) {
    if ((p ? a_p : a_s) <= 0) continue;
    const double speed = speed_of(p);
    if (!std::isfinite(speed) || !(speed > 0)) {
      result.ok = false;
      result.reason = std::string("the ") + (p ? "P" : "S") +
                      " pulse did not reach two monitoring points within run.duration_s; lengthen it";
      return result;
    }
    result.macro[p ? "wave_speed_p_m_s" : "wave_speed_s_m_s"] = speed;
    if (p == p_wave) measured = speed;
  }

  // Reflection at the reflection point: the incident pulse passes it before the reflected front arrives
  // from the far side, and the reflected one before the input side's own echo would.
  const Monitor& rp = monitors.back();
  const double d = rp.distance_m, pulse_m = measured * period;
  const double reflected_at = (2 * length_m - d) / measured, echo_at = (2 * length_m + d) / measured;
  if (d < 0.5 * pulse_m || length_m - d < 0.5 * pulse_m) {
    result.ok = false;
    result.reason = "monitors.reflection_point lies " + format_double(d) + " m from the input face and " +
                    format_double(length_m - d) + " m from the far one; both must exceed half the pulse's length (" +
                    format_double(0.5 * pulse_m) + " m at the measured speed) to tell the reflection from the pulse";
    return result;
  }
  if (reflected_at + 1.25 * period > s.duration_s) {
    result.ok = false;
    result.reason = "run.duration_s " + format_double(s.duration_s) + " s ends before the reflection has passed the "
                    "reflection point (" + format_double(reflected_at + 1.25 * period) + " s)";
    return result;
  }
  const std::vector<double> v_r = along(rp, p_wave);
  const double incident = signed_extreme(rec.times, v_r, 0, reflected_at);
  const double reflected = signed_extreme(rec.times, v_r, reflected_at, std::min(echo_at, reflected_at + 1.25 * period));
  result.macro["reflection_coefficient"] = incident != 0 ? reflected / incident : 0.0;

  // Energy: what the input put in, what the dashpots took out, what is left moving.
  result.macro["energy_input_J"] = forces.input_work_j();
  result.macro["energy_absorbed_J"] = -(forces.dashpot_work_j() - absorbed_before);
  result.macro["kinetic_energy_end_J"] = world.kinetic_energy();
  // The static loads (gravity, the walls' forces the boundaries keep) balance at rest; over the run their work
  // nearly cancels, and what is neither absorbed nor still moving is strain energy left in the strip or
  // energy the contacts dissipated by friction (docs/explanation/wave_strip.md).
  double gravity_work = 0;
  for (std::size_t i : disks_by_id(b))
    gravity_work += b.mass[i] * (world.settings().gravity_x_m_s2 * (b.x[i] - x_start[i]) +
                                 world.settings().gravity_y_m_s2 * (b.y[i] - y_start[i]));
  const double applied_work = forces.applied_work_j() - work_before_input;
  result.specimen_info["applied_force_work_J"] = applied_work;
  result.specimen_info["gravity_work_J"] = gravity_work;
  result.specimen_info["energy_unaccounted_J"] = result.macro["energy_input_J"] + applied_work + gravity_work -
                                                 result.macro["energy_absorbed_J"] - result.macro["kinetic_energy_end_J"];
  return result;
}

namespace {

class WaveStripTest : public PackedTest {
 public:
  std::string name() const override { return "wave_strip"; }
  std::string description() const override {
    return "wave strip: a pulse enters a bonded strip through an input boundary; recovery times, reflection, wave speeds";
  }
  std::vector<BoundaryRole> boundary_roles() const override {
    return {{"particle-wall", kPlatenGroup, "the strip's disks against the vessel's walls, until the boundaries replace them"}};
  }
  bool exact_scaling() const override { return false; }  // a dynamic test: inertia and gravity set its numbers
  std::vector<SceneSection> extra_sections() const override {
    return {{"boundaries", "each side's type (fixed, free, viscous, input, velocity) and dashpot coefficients xi, eta", false},
            {"medium", "the equivalent continuum behind the dashpots: E_d, nu_d, or the wave speeds", false},
            {"pulse", "the cosine pulse's amplitudes (P, S) and period", false},
            {"monitors", "monitoring points T1, T2, ... and the reflection point", false},
            {"run", "duration, gravity, recording, recovery threshold, quiet period", false}};
  }
  void check_extra_sections(const Scene& scene) const override { WaveStripSpec::from_scene(scene, scene.resolve({})); }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"total_recovery_time_s"}; }
  std::pair<std::string, std::string> curve_axes() const override { return {"", ""}; }  // velocity histories
  std::vector<OutputSpec> outputs(const Scene& scene) const override {
    std::vector<OutputSpec> out;
    std::size_t points = 0;
    try {
      points = WaveStripSpec::from_scene(scene, scene.resolve({})).points.size();
    } catch (const Error&) {
    }
    for (std::size_t k = 1; k <= points; ++k) {
      const std::string label = "T" + std::to_string(k);
      add_recovery_outputs(out, label, "run.recovery_fraction of the peak speed the pulse had at the point nearest the input");
    }
    out.push_back({"total_recovery_time_s", "s", "sum of the points' recovery times (Ma et al. 2022's fitness)", true,
                   kNonNegative});
    out.push_back({"reflection_coefficient", "1",
                   "reflected over incident particle velocity (signed peaks) at monitors.reflection_point: the P "
                   "wave's, or the S wave's for a pulse with no P part"});
    out.push_back({"wave_speed_p_m_s", "m/s", "P wave speed from the pulse's arrivals at T1, T2, ... (a P pulse only)",
                   false, kNonNegative});
    out.push_back({"wave_speed_s_m_s", "m/s", "S wave speed from the arrivals (an S pulse only)", false, kNonNegative});
    add_energy_outputs(out);
    add_quiet_outputs(out, "the");
    return out;
  }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_wave_strip(scene, parameters, options);
  }
};

}  // namespace

void register_wave_strip_test(LabTestRegistry& registry) { registry.add(std::make_unique<WaveStripTest>()); }

}  // namespace demcal::dem
