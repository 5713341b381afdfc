// run_command: an argument list without a shell, its output in files, its
// exit status, and a timeout that ends the whole process group.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "demcal/core/error.hpp"
#include "demcal/core/subprocess.hpp"

namespace fs = std::filesystem;
using demcal::CommandOutcome;
using demcal::run_command;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "demcal_subprocess_XXXXXX").string();
    path = ::mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A process is gone when it no longer exists or is a zombie nobody reaped yet.
bool gone(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  if (!stat) return true;
  std::string pid_text, name, state;
  stat >> pid_text >> name >> state;
  return state == "Z";
}

}  // namespace

TEST(RunCommand, ArgumentsReachTheProgramUnquotedAndItsOutputIsKept) {
  TempDir dir;
  // No shell: the spaces, quotes and $ stay inside their arguments.
  const CommandOutcome o = run_command({"/bin/sh", "-c", "printf '%s|' \"$@\"; echo oops >&2; exit 7", "sh",
                                        "two words", "$HOME", "'q'"},
                                       dir.path.string(), dir.file("out.txt"), dir.file("err.txt"), 10);
  EXPECT_TRUE(o.started);
  EXPECT_FALSE(o.timed_out);
  EXPECT_EQ(o.exit_status, 7);
  EXPECT_EQ(text_of(dir.file("out.txt")), "two words|$HOME|'q'|");
  EXPECT_EQ(text_of(dir.file("err.txt")), "oops\n");
  EXPECT_EQ(demcal::describe_outcome(o, "sh"), "sh exited with status 7");
}

TEST(RunCommand, RunsInItsFolderAndFindsRelativeProgramsThere) {
  TempDir dir;
  {
    std::ofstream script(dir.file("hello.sh"));
    script << "#!/bin/sh\npwd\n";
  }
  fs::permissions(dir.file("hello.sh"), fs::perms::owner_all);
  const CommandOutcome o = run_command({"./hello.sh"}, dir.path.string(), dir.file("out.txt"), dir.file("err.txt"), 10);
  EXPECT_EQ(o.exit_status, 0);
  EXPECT_EQ(text_of(dir.file("out.txt")), fs::canonical(dir.path).string() + "\n");
}

TEST(RunCommand, AProgramThatCannotRunSaysWhy) {
  TempDir dir;
  const CommandOutcome missing =
      run_command({"no_such_simulator_4711"}, dir.path.string(), dir.file("o"), dir.file("e"), 10);
  EXPECT_FALSE(missing.started);
  EXPECT_EQ(missing.reason, "command not found: no_such_simulator_4711 (not on PATH)");
  std::ofstream(dir.file("data.txt")) << "not a program\n";
  const CommandOutcome not_executable = run_command({"./data.txt"}, dir.path.string(), dir.file("o"), dir.file("e"), 10);
  EXPECT_FALSE(not_executable.started);
  EXPECT_NE(not_executable.reason.find("is not an executable file"), std::string::npos) << not_executable.reason;
  EXPECT_THROW(run_command({"true"}, dir.file("no_such_folder"), dir.file("o"), dir.file("e"), 10), demcal::Error);
  EXPECT_THROW(run_command({}, dir.path.string(), dir.file("o"), dir.file("e"), 10), demcal::Error);
}

TEST(RunCommand, ATimeoutKillsTheWholeProcessGroup) {
  TempDir dir;
  // The shell starts a grandchild that would outlive a kill of the shell alone.
  const auto start = std::chrono::steady_clock::now();
  const CommandOutcome o = run_command({"/bin/sh", "-c", "sleep 60 & echo $! > child.pid; wait"}, dir.path.string(),
                                       dir.file("o"), dir.file("e"), 0.5);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(o.started);
  EXPECT_TRUE(o.timed_out);
  EXPECT_EQ(o.reason, "timed out after 0.5 s (its process group was killed)");
  EXPECT_LT(wall_s, 5.0);
  const pid_t child = std::atoi(text_of(dir.file("child.pid")).c_str());
  ASSERT_GT(child, 0);
  for (int k = 0; k < 100 && !gone(child); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(gone(child)) << "the grandchild " << child << " survived the timeout";
}

TEST(RunCommand, WhatItLeavesRunningInItsGroupEndsWithIt) {
  TempDir dir;
  const CommandOutcome o = run_command({"/bin/sh", "-c", "sleep 60 & echo $! > child.pid; exit 0"}, dir.path.string(),
                                       dir.file("o"), dir.file("e"), 10);
  EXPECT_EQ(o.exit_status, 0);
  const pid_t child = std::atoi(text_of(dir.file("child.pid")).c_str());
  for (int k = 0; k < 100 && !gone(child); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(gone(child));
}
