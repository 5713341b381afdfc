// The wall-clock limit and progress line of a powder test (run_watch.hpp).
#include "demcal/dem/run_watch.hpp"

#include <algorithm>
#include <cstdint>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/wall_timeout.hpp"

namespace demcal::dem {

const std::vector<std::string>& SettleRun::keys() {
  static const std::vector<std::string> names = {"max_time_s", "fill_time_s", "check_every_s", "settle_kinetic_ratio",
                                                 "max_wall_s"};
  return names;
}

void SettleRun::read(const Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& run) {
  for (const auto& [key, target] : std::vector<std::pair<const char*, double*>>{
           {"max_time_s", &max_time_s}, {"fill_time_s", &fill_time_s}, {"check_every_s", &check_every_s},
           {"settle_kinetic_ratio", &settle_kinetic_ratio}, {"max_wall_s", &max_wall_s}})
    read_section_number(scene, parameters, "run", run, key, *target, false);
}

void SettleRun::validate(const std::string& where) const {
  if (!(max_time_s > 0)) throw Error(where + ".max_time_s must be positive");
  if (!(fill_time_s >= 0)) throw Error(where + ".fill_time_s must be >= 0");
  if (!(check_every_s > 0 && check_every_s < max_time_s)) throw Error(where + ".check_every_s must lie in (0, max_time_s)");
  if (!(settle_kinetic_ratio > 0 && settle_kinetic_ratio < 1))
    throw Error(where + ".settle_kinetic_ratio must lie in (0, 1)");
  if (!(max_wall_s > 0)) throw Error(where + ".max_wall_s must be positive");
}

RunWatch::RunWatch(std::string test, double max_wall_s, std::chrono::steady_clock::time_point start, double end_time_s,
                   const std::string& progress_label, bool show_progress)
    : test_(std::move(test)), max_wall_s_(max_wall_s), end_time_s_(end_time_s), start_(start) {
  if (show_progress) progress_ = std::make_unique<Progress>(progress_label, 100);
}

bool RunWatch::carry_on(double t) {
  if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() > max_wall_s_) return false;
  if (progress_) {
    const int percent = std::min(100, static_cast<int>(100 * t / end_time_s_));
    if (percent > shown_percent_) progress_->advance(static_cast<std::uint64_t>(percent - shown_percent_));
    shown_percent_ = std::max(shown_percent_, percent);
  }
  return true;
}

std::string RunWatch::timeout_reason() const {
  return wall_timeout_reason("the " + test_ + " took longer than run.max_wall_s " + format_double(max_wall_s_) +
                             " s of wall time");
}

void RunWatch::set_note(std::string note) {
  if (progress_) progress_->set_note(std::move(note));
}

void RunWatch::finish() {
  if (progress_) progress_->finish();
}

}  // namespace demcal::dem
