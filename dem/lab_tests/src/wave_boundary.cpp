// The boundaries, pulse and records the 2D wave tests share (wave_boundary.hpp).
#include "demcal/dem/wave_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/core/wall_timeout.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

// Per disk, the length of side its dashpots stand for (0 off the side): 2R, or
// the tributary length along the side (DashpotWidth), from the disk centres'
// coordinate along it; the side runs from `from_m` to `to_m`.
std::vector<double> dashpot_widths(const Bodies& b, const std::vector<char>& on_side, const BoundarySide& side,
                                   DashpotWidth width) {
  std::vector<double> out(b.size(), 0.0);
  std::vector<std::size_t> disks;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (on_side[i]) disks.push_back(i);
  if (width == DashpotWidth::diameter) {
    for (std::size_t i : disks) out[i] = 2 * b.radius[i];
    return out;
  }
  auto along = [&](std::size_t i) { return side.along_x ? b.x[i] : b.y[i]; };
  std::sort(disks.begin(), disks.end(), [&](std::size_t p, std::size_t q) { return along(p) < along(q); });
  // Where the side passes from disk p to the next disk q: half-way, or where they would touch.
  auto split = [&](std::size_t p, std::size_t q) {
    if (width == DashpotWidth::tributary) return 0.5 * (along(p) + along(q));
    return along(p) + (along(q) - along(p)) * b.radius[p] / (b.radius[p] + b.radius[q]);
  };
  for (std::size_t k = 0; k < disks.size(); ++k) {
    const double from = k == 0 ? side.from_m : split(disks[k - 1], disks[k]);
    const double to = k + 1 == disks.size() ? side.to_m : split(disks[k], disks[k + 1]);
    out[disks[k]] = to - from;
  }
  return out;
}

}  // namespace

SideSpec read_boundary_side(const Scene& scene, const std::map<std::string, double>& parameters,
                            const nlohmann::json& o, const std::string& where) {
  const std::string& origin = scene.origin();
  require_known_fields(o, {"type", "xi", "eta", "dashpot_width", "note"}, origin + ": " + where);
  if (!o.contains("type") || !o.at("type").is_string())
    throw Error(origin + ": " + where + ".type: missing (\"fixed\", \"free\", \"viscous\", \"input\" or \"velocity\")");
  const std::string type = o.at("type").get<std::string>();
  SideSpec s;
  if (type == "fixed") s.type = BoundaryType::fixed;
  else if (type == "free") s.type = BoundaryType::free;
  else if (type == "viscous") s.type = BoundaryType::viscous;
  else if (type == "input") s.type = BoundaryType::input;
  else if (type == "velocity") s.type = BoundaryType::velocity;
  else throw Error(origin + ": " + where + ".type: \"" + type + "\" (allowed: fixed, free, viscous, input, velocity)");
  if (s.has_dashpots()) {
    read_section_number(scene, parameters, where, o, "xi", s.xi, true);
    read_section_number(scene, parameters, where, o, "eta", s.eta, true);
    if (s.xi < 0) throw Error(origin + ": " + where + ".xi must be >= 0 (got " + format_double(s.xi) + ")");
    if (s.eta < 0) throw Error(origin + ": " + where + ".eta must be >= 0 (got " + format_double(s.eta) + ")");
    if (o.contains("dashpot_width")) {
      const nlohmann::json& w = o.at("dashpot_width");
      if (w == "diameter") s.width = DashpotWidth::diameter;
      else if (w == "tributary") s.width = DashpotWidth::tributary;
      else if (w == "tributary_by_radius") s.width = DashpotWidth::tributary_by_radius;
      else throw Error(origin + ": " + where + ".dashpot_width: " + w.dump() +
                       " (allowed: \"diameter\", \"tributary\", \"tributary_by_radius\")");
    }
  } else if (o.contains("xi") || o.contains("eta") || o.contains("dashpot_width")) {
    throw Error(origin + ": " + where + ": xi, eta and dashpot_width belong to a viscous or input side, not a " + type +
                " one");
  }
  return s;
}

double MediumSpec::p_speed_formula_m_s(double rho) const {
  return p_formula == PSpeedFormula::plane_stress ? p_speed_plane_stress_m_s(rho) : p_speed_ma2022_m_s(rho);
}
double MediumSpec::p_speed_ma2022_m_s(double rho) const {
  return std::sqrt(e_d_pa * (1 - nu_d) / (rho * (1 + nu_d) * (1 - 2 * nu_d)));
}
double MediumSpec::p_speed_plane_stress_m_s(double rho) const { return std::sqrt(e_d_pa / (rho * (1 - nu_d * nu_d))); }
double MediumSpec::s_speed_formula_m_s(double rho) const { return std::sqrt(e_d_pa / (2 * rho * (1 + nu_d))); }
double MediumSpec::p_speed_m_s(double rho) const {
  return given_p_speed_m_s > 0 ? given_p_speed_m_s : p_speed_formula_m_s(rho);
}
double MediumSpec::s_speed_m_s(double rho) const {
  return given_s_speed_m_s > 0 ? given_s_speed_m_s : s_speed_formula_m_s(rho);
}

MediumSpec MediumSpec::read(const Scene& scene, const std::map<std::string, double>& parameters,
                            const nlohmann::json& m, const std::string& where, const std::vector<std::string>& extra_keys) {
  const std::string& origin = scene.origin();
  std::vector<std::string> keys = {"E_d_Pa", "nu_d", "wave_speed_p_m_s", "wave_speed_s_m_s", "p_speed_formula", "note"};
  keys.insert(keys.end(), extra_keys.begin(), extra_keys.end());
  require_known_fields(m, keys, origin + ": " + where);
  MediumSpec s;
  if (m.contains("p_speed_formula")) {
    const nlohmann::json& f = m.at("p_speed_formula");
    if (f == "ma2022")
      s.p_formula = PSpeedFormula::ma2022;
    else if (f == "plane_stress")
      s.p_formula = PSpeedFormula::plane_stress;
    else
      throw Error(origin + ": " + where + ".p_speed_formula must be \"ma2022\" or \"plane_stress\" (got " + f.dump() + ")");
  }
  read_section_number(scene, parameters, where, m, "wave_speed_p_m_s", s.given_p_speed_m_s, false);
  read_section_number(scene, parameters, where, m, "wave_speed_s_m_s", s.given_s_speed_m_s, false);
  const bool given = s.given_p_speed_m_s > 0 && s.given_s_speed_m_s > 0;
  read_section_number(scene, parameters, where, m, "E_d_Pa", s.e_d_pa, !given);
  read_section_number(scene, parameters, where, m, "nu_d", s.nu_d, !given);
  if (m.contains("E_d_Pa") && !(s.e_d_pa > 0)) throw Error(origin + ": " + where + ".E_d_Pa must be positive");
  if (m.contains("nu_d") && !(s.nu_d > -1 && s.nu_d < 0.5)) throw Error(origin + ": " + where + ".nu_d must lie in (-1, 0.5)");
  if (m.contains("wave_speed_p_m_s") && !(s.given_p_speed_m_s > 0))
    throw Error(origin + ": " + where + ".wave_speed_p_m_s must be positive");
  if (m.contains("wave_speed_s_m_s") && !(s.given_s_speed_m_s > 0))
    throw Error(origin + ": " + where + ".wave_speed_s_m_s must be positive");
  return s;
}

PulseSpec PulseSpec::read(const Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& p,
                          const std::string& where) {
  const std::string& origin = scene.origin();
  require_known_fields(p, {"p_amplitude_m_s", "s_amplitude_m_s", "period_s", "note"}, origin + ": " + where);
  PulseSpec s;
  read_section_number(scene, parameters, where, p, "p_amplitude_m_s", s.p_amplitude_m_s, false);
  read_section_number(scene, parameters, where, p, "s_amplitude_m_s", s.s_amplitude_m_s, false);
  read_section_number(scene, parameters, where, p, "period_s", s.period_s, false);
  if (!(s.p_amplitude_m_s >= 0 && s.s_amplitude_m_s >= 0 && s.p_amplitude_m_s + s.s_amplitude_m_s > 0))
    throw Error(origin + ": " + where + ": p_amplitude_m_s and s_amplitude_m_s must be >= 0, and one of them positive");
  if (!(s.period_s > 0)) throw Error(origin + ": " + where + ".period_s must be positive");
  return s;
}

BoundarySideSummary install_boundary_side(World& world, const BoundarySide& side, const SideSpec& spec,
                                          const std::function<DiskImpedance(std::size_t disk)>& impedance,
                                          BoundaryForces& boundary, const std::string& origin) {
  Bodies& b = world.bodies;
  const double t = world.settings().thickness_m;
  std::vector<double> fx, fy, moment;
  world.wall_forces_on_disks(fx, fy, moment, side.wall);
  std::vector<char> touching(b.size(), 0);
  const ContactSet& wp = world.wall_pairs();
  for (std::size_t k = 0; k < wp.size(); ++k)
    if (static_cast<std::size_t>(wp.j[k]) == side.wall && (wp.flags[k] & kTouching))
      touching[static_cast<std::size_t>(wp.i[k])] = 1;
  // Disks a hair off the wall belong to the side too (a bonded block settles millimetres away from a frictionless
  // wall); they keep no static force, having none from the wall.
  if (side.near_gap_fraction > 0) {
    const Wall& w = world.walls[side.wall];
    for (std::size_t i = 0; i < b.size(); ++i) {
      const double gap = (side.along_x ? std::abs(b.y[i] - w.y0) : std::abs(b.x[i] - w.x0)) - b.radius[i];
      if (gap <= side.near_gap_fraction * b.radius[i]) touching[i] = 1;
    }
  }
  BoundarySide extent = side;
  if (!(extent.to_m > extent.from_m)) {
    extent.to_m = extent.from_m;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (touching[i]) extent.to_m = std::max(extent.to_m, (side.along_x ? b.x[i] : b.y[i]) + b.radius[i]);
  }
  const std::vector<double> width_m = dashpot_widths(b, touching, extent, spec.width);
  BoundarySideSummary summary;
  summary.length_m = extent.to_m - extent.from_m;
  for (std::size_t i : disks_by_id(b)) {  // the boundary's sums then do not depend on the disks' storage order
    if (!touching[i]) continue;
    ++summary.disks;
    summary.covered_m += 2 * b.radius[i];
    summary.dashpot_m += width_m[i];
    if (spec.type == BoundaryType::fixed || spec.type == BoundaryType::velocity) {
      b.fixed[i] = 1;
      b.vx[i] = b.vy[i] = b.w[i] = 0;
    }
    // A fixed disk keeps F_app too: it does not move it, but its unbalanced force is then the wave's
    // reaction alone, not the wall's static load as well.
    const DiskImpedance z = impedance(i);
    BoundaryDisk d;
    d.disk = i;
    d.outward_nx = -side.inward[0];
    d.outward_ny = -side.inward[1];
    d.applied_fx_n = fx[i];
    d.applied_fy_n = fy[i];
    d.applied_moment_nm = moment[i];
    d.normal_dashpot_n_s_m = width_m[i] * t * spec.xi * z.rho_kg_m3 * z.c_p_m_s;
    d.shear_dashpot_n_s_m = width_m[i] * t * spec.eta * z.rho_kg_m3 * z.c_s_m_s;
    d.input = spec.type == BoundaryType::input;
    d.prescribed = spec.type == BoundaryType::velocity;
    // The dashpot is explicit (it acts on the last half step's velocity): c dt / m must stay well below 2, the
    // update's own limit, or the boundary disk's velocity flips sign each step and grows.
    const double stiffest = std::max(d.normal_dashpot_n_s_m, d.shear_dashpot_n_s_m) * world.dt_s() / b.mass[i];
    if (stiffest > 1.0)
      throw Error(origin + ": boundaries." + side.name + ": xi " + format_double(spec.xi) + " / eta " +
                  format_double(spec.eta) + " make a dashpot of c dt / m = " + format_double(stiffest) +
                  " on a boundary disk, above 1: the explicit update would be unstable (smaller coefficients, or a "
                  "smaller time step)");
    boundary.add_disk(d);
  }
  if (summary.disks == 0 && spec.type != BoundaryType::free)  // a free side the model left has no load to keep
    throw Error(origin + ": boundaries." + side.name + ": no disk touches the " + side.name +
                " wall at rest, so the side has no boundary particles");
  world.walls[side.wall].active = false;
  return summary;
}

void record_boundary_side(TestResult& result, const std::string& name, const SideSpec& spec,
                          const BoundarySideSummary& summary) {
  result.specimen_info["boundary_disks_" + name] = static_cast<double>(summary.disks);
  result.specimen_info["boundary_coverage_" + name] = summary.covered_m / summary.length_m;
  if (spec.has_dashpots()) result.specimen_info["dashpot_coverage_" + name] = summary.dashpot_m / summary.length_m;
}

double run_quiet_period(World& world, double quiet_time_s) {
  const Bodies& b = world.bodies;
  const std::vector<double> x_rest = b.x, y_rest = b.y;
  world.run(static_cast<std::uint64_t>(std::ceil(quiet_time_s / world.dt_s())));
  double drift2 = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    drift2 = std::max(drift2, (b.x[i] - x_rest[i]) * (b.x[i] - x_rest[i]) + (b.y[i] - y_rest[i]) * (b.y[i] - y_rest[i]));
  return std::sqrt(drift2);
}

void add_recovery_outputs(std::vector<OutputSpec>& out, const std::string& label, const std::string& below) {
  out.push_back({"recovery_time_s_" + label, "s",
                 "time after which the speed at " + label + " stays below " + below + " (run.duration_s if it never does)",
                 true, kNonNegative});
  out.push_back({"recovered_" + label, "1", "1 when " + label + " fell quiet within run.duration_s, else 0", true, kFlag});
}

void add_energy_outputs(std::vector<OutputSpec>& out) {
  out.push_back({"energy_input_J", "J", "work of the input boundary's wave on the model"});
  out.push_back({"energy_absorbed_J", "J", "work the dashpots took out of the model", true, kNonNegative});
  out.push_back({"kinetic_energy_end_J", "J", "kinetic energy at the end of the run", true, kNonNegative});
}

void add_quiet_outputs(std::vector<OutputSpec>& out, const std::string& ratio_of) {
  out.push_back({"quiet_drift_m", "m", "largest move of a disk over the quiet period after the walls were replaced",
                 true, kNonNegative});
  out.push_back({"quiet_force_ratio", "1", ratio_of + " mean unbalanced-force ratio at the end of the quiet period", true,
                 kNonNegative});
}

void Monitor::collect(const Bodies& b, double radius_m, const std::string& origin, int group) {
  disks.clear();
  for (std::size_t i : disks_by_id(b))
    if (std::hypot(b.x[i] - x_m, b.y[i] - y_m) <= radius_m && !b.fixed[i] && (group < 0 || b.group[i] == group))
      disks.push_back(i);
  if (disks.empty())
    throw Error(origin + ": monitors: no free disk within " + format_double(radius_m) + " m of point " + label + " (" +
                format_double(x_m) + ", " + format_double(y_m) + " m)");
}

void Monitor::record(const Bodies& b) {
  double sx = 0, sy = 0;
  for (std::size_t i : disks) {
    sx += b.vx[i];
    sy += b.vy[i];
  }
  vx.push_back(sx / static_cast<double>(disks.size()));
  vy.push_back(sy / static_cast<double>(disks.size()));
}

std::vector<double> Monitor::speeds() const {
  std::vector<double> speed(vx.size());
  for (std::size_t q = 0; q < speed.size(); ++q) speed[q] = std::hypot(vx[q], vy[q]);
  return speed;
}

void WaveRecord::record(const World& world) {
  times.push_back(world.time_s());
  kinetic.push_back(world.kinetic_energy());
  for (Monitor& m : monitors) m.record(world.bodies);
}

void WaveRecord::add_series(TestResult& result) const {
  result.series.emplace_back("time_s", times);
  result.series.emplace_back("kinetic_energy_J", kinetic);
  for (const Monitor& m : monitors) {
    result.series.emplace_back("vx_" + m.label + "_m_s", m.vx);
    result.series.emplace_back("vy_" + m.label + "_m_s", m.vy);
  }
}

void run_recording(World& world, WaveRecord& record, const RecordedRun& run, TestResult& result) {
  std::unique_ptr<Progress> progress;
  if (run.show_progress) progress = std::make_unique<Progress>(run.progress_label, 100);
  int shown = 0;
  if (run.record_first) record.record(world);
  result.ok = true;
  while (world.time_s() < run.end_time_s) {
    world.run(run.steps_per_record);
    record.record(world);
    const std::string unstable = wave_instability(world.bodies, world.time_s(), run.max_speed_m_s, run.max_speed_reason);
    if (!unstable.empty()) {
      result.ok = false;
      result.reason = unstable;
      break;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - run.start).count() > run.max_wall_s) {
      result.ok = false;
      result.reason = wall_timeout_reason("the run took longer than run.max_wall_s " + format_double(run.max_wall_s) + " s");
      break;
    }
    if (progress) {
      const int percent = std::min(100, static_cast<int>(100 * world.time_s() / run.end_time_s));
      if (percent > shown) progress->advance(static_cast<std::uint64_t>(percent - shown));
      shown = std::max(shown, percent);
    }
    if (run.done && run.done()) break;
  }
  if (progress) progress->finish();
}

std::string wave_instability(const Bodies& b, double time_s, double max_speed_m_s, const std::string& reason) {
  double fastest = 0;
  bool finite = true;
  for (std::size_t i = 0; i < b.size(); ++i) {
    finite = finite && std::isfinite(b.vx[i]) && std::isfinite(b.vy[i]);
    fastest = std::max(fastest, std::abs(b.vx[i]) + std::abs(b.vy[i]));
  }
  if (finite && fastest <= max_speed_m_s) return "";
  return "unstable at t = " + format_double(time_s) + " s: " +
         (finite ? "a disk moves faster than " + reason : std::string("non-finite velocities"));
}

}  // namespace demcal::dem
