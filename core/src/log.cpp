#include "demcal/core/log.hpp"

#include <cstdio>
#include <mutex>

namespace demcal::log {
namespace {

std::string& program_name() {
  static std::string name = "demcal";
  return name;
}
Level current_level = Level::Normal;
std::mutex output_mutex;

void emit(const char* tag, const std::string& message) {
  std::lock_guard<std::mutex> lock(output_mutex);
  std::fprintf(stderr, "%s: %s%s\n", program_name().c_str(), tag, message.c_str());
  std::fflush(stderr);
}

}  // namespace

void set_program(const std::string& name) { program_name() = name; }
void set_level(Level level) { current_level = level; }
Level level() { return current_level; }
const std::string& program() { return program_name(); }

void info(const std::string& message) {
  if (current_level >= Level::Normal) emit("", message);
}
void detail(const std::string& message) {
  if (current_level >= Level::Verbose) emit("", message);
}
void warn(const std::string& message) { emit("warning: ", message); }
void error(const std::string& message) { emit("error: ", message); }

}  // namespace demcal::log
