#include "demcal/core/progress.hpp"

#include <cmath>
#include <cstdio>
#include <unistd.h>

#include "demcal/core/log.hpp"

namespace demcal {

std::string format_duration(double seconds) {
  char buffer[64];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 60) {
    std::snprintf(buffer, sizeof(buffer), "%.1fs", seconds);
  } else if (seconds < 3600) {
    std::snprintf(buffer, sizeof(buffer), "%dm%02ds", static_cast<int>(seconds / 60), static_cast<int>(seconds) % 60);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%dh%02dm", static_cast<int>(seconds / 3600),
                  (static_cast<int>(seconds) % 3600) / 60);
  }
  return buffer;
}

Progress::Progress(std::string label, std::uint64_t total, double log_interval_s)
    : label_(std::move(label)),
      total_(total),
      log_interval_s_(log_interval_s),
      terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() { finish(); }

std::string Progress::line() const {
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  char buffer[256];
  double percent = total_ ? 100.0 * static_cast<double>(done_) / static_cast<double>(total_) : 100.0;
  std::string eta = "?";
  if (done_ > 0 && total_ >= done_)
    eta = format_duration(elapsed * static_cast<double>(total_ - done_) / static_cast<double>(done_));
  std::snprintf(buffer, sizeof(buffer), "%s: %llu/%llu (%.0f%%), elapsed %s, ETA %s", label_.c_str(),
                static_cast<unsigned long long>(done_), static_cast<unsigned long long>(total_), percent,
                format_duration(elapsed).c_str(), eta.c_str());
  std::string text = buffer;
  if (units_ > 0 && elapsed > 0) {
    std::snprintf(buffer, sizeof(buffer), ", %.3g %s/s", units_ / elapsed,
                  units_name_.empty() ? "units" : units_name_.c_str());
    text += buffer;
  }
  if (!note_.empty()) text += "; " + note_;
  return text;
}

void Progress::set_note(std::string note) {
  std::lock_guard<std::mutex> lock(mutex_);
  note_ = std::move(note);
}

void Progress::advance(std::uint64_t count, double units) {
  std::lock_guard<std::mutex> lock(mutex_);
  done_ += count;
  units_ += units;
  draw(false);
}

void Progress::draw(bool final_line) {
  if (log::level() == log::Level::Quiet) return;
  auto now = std::chrono::steady_clock::now();
  double since = std::chrono::duration<double>(now - last_draw_).count();
  double interval = terminal_ ? 0.2 : log_interval_s_;
  if (!final_line && since < interval) return;
  last_draw_ = now;
  std::string text = log::program() + ": " + line();
  if (terminal_) {
    std::fprintf(stderr, "\r%s\033[K%s", text.c_str(), final_line ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s\n", text.c_str());
  }
  std::fflush(stderr);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  draw(true);
}

}  // namespace demcal
