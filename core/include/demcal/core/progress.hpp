#pragma once
// A progress line for long loops: done/total, percent, rate and ETA on stderr.
// On a terminal it redraws one line (at most every 0.2 s); in a log file it
// prints a line at most every `log_interval_s` seconds, so CI logs stay short.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace demcal {

class Progress {
 public:
  Progress(std::string label, std::uint64_t total, double log_interval_s = 10.0);
  ~Progress();
  // Thread-safe; `units` is an extra count shown as a rate (e.g. particle-steps).
  void advance(std::uint64_t count = 1, double units = 0.0);
  void set_units_name(std::string name) { units_name_ = std::move(name); }
  // What the loop is doing now ("discharging: 40 % out"), shown at the line's end; thread-safe.
  void set_note(std::string note);
  void finish();
  std::string line() const;  // the text of the current line

 private:
  void draw(bool final_line);

  std::string label_;
  std::string units_name_;
  std::string note_;
  std::uint64_t total_;
  std::uint64_t done_ = 0;
  double units_ = 0.0;
  double log_interval_s_;
  bool terminal_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  mutable std::mutex mutex_;
};

// "1h02m", "3m05s", "12.3s"
std::string format_duration(double seconds);

}  // namespace demcal
