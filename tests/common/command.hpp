#pragma once
// Runs a demcal executable as a user would and captures its exit code,
// stdout and stderr, for the command-line tests.
#include <gtest/gtest.h>

#include "scratch.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace demcal::test {

struct CommandResult {
  int code = -1;
  std::string out;
  std::string err;
};

inline std::string temp_path(const std::string& name) {
  return scratch_path(name);
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs a shell command line; `label` names its captured output files.
inline CommandResult run_command(const std::string& command_line, const std::string& label) {
  std::string out = temp_path(label + ".stdout"), err = temp_path(label + ".stderr");
  int status = std::system((command_line + " >" + out + " 2>" + err).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

inline CommandResult run_program(const std::string& program, const std::string& arguments) {
  return run_command(std::string(DEMCAL_BIN_DIR) + "/" + program + " " + arguments, program);
}

// A failed call prints exactly one line, "<program>: error: ...", containing `fragment`.
inline void expect_one_line_error(const CommandResult& r, const std::string& program, const std::string& fragment) {
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(program + ": error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

}  // namespace demcal::test
