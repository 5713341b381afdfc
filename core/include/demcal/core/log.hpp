#pragma once
// Messages to stderr, prefixed with the program name: stdout stays free for
// results. Verbosity is process-wide and set once by the executable.
#include <string>

namespace demcal::log {

enum class Level { Quiet = 0, Normal = 1, Verbose = 2 };

void set_program(const std::string& name);
void set_level(Level level);
Level level();
const std::string& program();

void info(const std::string& message);     // shown unless quiet
void detail(const std::string& message);   // shown when verbose
void warn(const std::string& message);     // always shown, "warning:" prefix
void error(const std::string& message);    // always shown, "error:" prefix

}  // namespace demcal::log
