#pragma once
// Runs an external program the way a calibration needs it: an argument list
// (no shell, so no quoting surprises), in a folder of its own, its stdout and
// stderr kept in files, as the leader of its own process group so that a
// timeout ends everything it started.
#include <string>
#include <vector>

namespace demcal {

struct CommandOutcome {
  bool started = false;    // false: the program could not be run (`reason` says why)
  bool timed_out = false;  // killed (with its process group) after the timeout
  int exit_status = -1;    // when it exited by itself
  int signal = 0;          // when a signal ended it
  std::string reason;
  double wall_s = 0;
};

// `argv[0]` is found on PATH unless it holds a '/' (then it is taken relative
// to `cwd`, as a shell would). Blocks until the program ends or `timeout_s`
// passes; then SIGKILLs its whole process group. Whatever it leaves running in
// its group when it exits is killed too. Never throws for a program that fails
// or cannot start; throws an Error for an empty argv or an unusable cwd or
// output file (a fault of ours, not of the command).
CommandOutcome run_command(const std::vector<std::string>& argv, const std::string& cwd, const std::string& stdout_path,
                           const std::string& stderr_path, double timeout_s);

// One line describing the outcome for a failed point ("exit status 2",
// "killed by signal 9", "timed out after 600 s", or why it did not start).
std::string describe_outcome(const CommandOutcome& outcome, const std::string& program);

}  // namespace demcal
