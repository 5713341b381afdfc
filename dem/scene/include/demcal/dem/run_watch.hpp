#pragma once
// What every powder test keeps an eye on while it steps: the wall-clock
// limit (run.max_wall_s, counted from the run's start) and the progress line
// over its simulated time; and the "run" keys of a test that fills, acts and
// settles (the funnel heap, the baffle lift).
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/core/progress.hpp"
#include "demcal/dem/scene.hpp"

namespace demcal::dem {

// Each optional; a test sets its own defaults before reading.
struct SettleRun {
  double max_time_s = 5, fill_time_s = 0.05, check_every_s = 0.002, settle_kinetic_ratio = 1e-6, max_wall_s = 600;

  static const std::vector<std::string>& keys();
  // Reads the keys present in `run` (values or expressions of the parameters).
  void read(const Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& run);
  // An Error naming `where` ("file: run") and the key that is out of range.
  void validate(const std::string& where) const;
};

class RunWatch {
 public:
  // `test` names the test in the timeout ("the heap took longer ..."); `progress_label` heads the progress line,
  // shown when `show_progress`; `end_time_s` is the simulated time the line counts to.
  RunWatch(std::string test, double max_wall_s, std::chrono::steady_clock::time_point start, double end_time_s,
           const std::string& progress_label, bool show_progress);

  // At simulated time t: false once past max_wall_s (timeout_reason() says so), else true after moving the line on.
  bool carry_on(double t);
  std::string timeout_reason() const;
  // The stage the run is in, at the progress line's end.
  void set_note(std::string note);
  void finish();

 private:
  std::string test_;
  double max_wall_s_, end_time_s_;
  std::chrono::steady_clock::time_point start_;
  std::unique_ptr<Progress> progress_;
  int shown_percent_ = 0;
};

}  // namespace demcal::dem
