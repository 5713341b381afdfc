// The fill, discharge and settle stages of a funnel heap (funnel_discharge.hpp).
#include "demcal/dem/funnel_discharge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem {

const std::vector<std::string>& FunnelRun::keys() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = SettleRun::keys();
    all.insert(all.end(), {"jam_time_s", "discharged_fraction"});
    return all;
  }();
  return names;
}

void FunnelRun::read(const Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& run) {
  SettleRun::read(scene, parameters, run);
  read_section_number(scene, parameters, "run", run, "jam_time_s", jam_time_s, false);
  read_section_number(scene, parameters, "run", run, "discharged_fraction", discharged_fraction, false);
}

void FunnelRun::validate(const std::string& where) const {
  SettleRun::validate(where);
  if (!(jam_time_s > 0)) throw Error(where + ".jam_time_s must be positive");
  if (!(discharged_fraction > 0 && discharged_fraction <= 1)) throw Error(where + ".discharged_fraction must lie in (0, 1]");
}

FunnelDischarge::FunnelDischarge(const FunnelRun& run, std::size_t total, FunnelWords words,
                                 std::chrono::steady_clock::time_point start, bool show_progress)
    : run_(run),
      total_(total),
      left_behind_(static_cast<std::size_t>(std::floor((1 - run.discharged_fraction) * static_cast<double>(total)))),
      remaining_(total),
      words_(std::move(words)),
      watch_(words_.test, run.max_wall_s, start, run.max_time_s, words_.label + " (% of run.max_time_s)",
             show_progress) {}

void FunnelDischarge::finish_progress() { watch_.finish(); }

FunnelDischarge::Next FunnelDischarge::after_fill(double t) {
  if (t < run_.fill_time_s) return Next::step_on;
  opened_at_s_ = last_drop_at_s_ = t;
  stage_ = Stage::discharge;
  watch_.set_note("discharging");
  return Next::open_gate;
}

FunnelDischarge::Next FunnelDischarge::after_count(double t, std::size_t in_funnel) {
  if (in_funnel < remaining_) last_drop_at_s_ = t;
  remaining_ = in_funnel;
  watch_.set_note("discharging: " + std::to_string(total_ - remaining_) + " of " + std::to_string(total_) + " " +
                  words_.particles + " out");
  if (remaining_ <= left_behind_) {
    flow_time_s_ = t - opened_at_s_;
    stage_ = Stage::settle;
    watch_.set_note("settling");
  } else if (t - last_drop_at_s_ > run_.jam_time_s) {
    return fail("the funnel jammed: " + std::to_string(remaining_) + " of " + std::to_string(total_) + " " +
                words_.particles + " still in it " + format_double(t - opened_at_s_) +
                " s after it opened (none left it for run.jam_time_s " + format_double(run_.jam_time_s) + " s); widen " +
                words_.outlet_key + " or steepen funnel.wall_angle_deg");
  }
  return Next::step_on;
}

bool FunnelDischarge::settled(double kinetic_j, double potential_j) {
  char ratio[32];
  std::snprintf(ratio, sizeof(ratio), "%.2g", kinetic_j / potential_j);
  watch_.set_note(std::string("settling: kinetic / potential energy ") + ratio + ", asked below " +
                  format_double(run_.settle_kinetic_ratio));
  if (!(kinetic_j < run_.settle_kinetic_ratio * potential_j)) return false;
  settled_ratio_ = kinetic_j / potential_j;
  return true;
}

FunnelDischarge::Next FunnelDischarge::overtime(double kinetic_j, double potential_j) {
  if (stage_ == Stage::settle)
    return fail("the heap did not settle within run.max_time_s " + format_double(run_.max_time_s) +
                " s (kinetic / potential energy " + format_double(kinetic_j / potential_j) + ", asked below " +
                format_double(run_.settle_kinetic_ratio) + ")");
  return fail("the funnel had not discharged within run.max_time_s " + format_double(run_.max_time_s) + " s (" +
              std::to_string(remaining_) + " of " + std::to_string(total_) + " " + words_.particles + " left)");
}

FunnelDischarge::Next FunnelDischarge::fail(std::string why) {
  reason_ = std::move(why);
  return Next::failed;
}

}  // namespace demcal::dem
