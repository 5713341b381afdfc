#include "demcal/core/subprocess.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/wall_timeout.hpp"

namespace demcal {
namespace {

bool is_executable_file(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// The program's path, searched on PATH in this process: between fork and exec
// only async-signal-safe calls are allowed, and execvp's search is not one.
std::string resolve_program(const std::string& program, const std::string& cwd) {
  if (program.find('/') != std::string::npos) return program[0] == '/' ? program : cwd + "/" + program;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = dirs.find(':', start);
    std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/" + program;
    if (is_executable_file(candidate)) return candidate;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return "";
}

int open_output(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(path + ": cannot write the command's output (" + std::strerror(errno) + ")");
  return fd;
}

}  // namespace

CommandOutcome run_command(const std::vector<std::string>& argv, const std::string& cwd, const std::string& stdout_path,
                           const std::string& stderr_path, double timeout_s) {
  if (argv.empty() || argv[0].empty()) throw Error("run_command: an empty command");
  struct stat st;
  if (::stat(cwd.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) throw Error(cwd + ": the command's folder does not exist");
  CommandOutcome outcome;
  const std::string program = resolve_program(argv[0], cwd);
  if (program.empty()) {
    outcome.reason = "command not found: " + argv[0] + " (not on PATH)";
    return outcome;
  }
  if (!is_executable_file(program)) {
    outcome.reason = "cannot run " + argv[0] + ": " + program + " is not an executable file";
    return outcome;
  }
  const int out_fd = open_output(stdout_path);
  int err_fd = -1;
  try {
    err_fd = open_output(stderr_path);
  } catch (...) {
    ::close(out_fd);
    throw;
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // The child reports a failed exec through this pipe (closed on a good exec).
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    ::close(out_fd);
    ::close(err_fd);
    throw Error(std::string("run_command: pipe: ") + std::strerror(errno));
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {out_fd, err_fd, report[0], report[1]}) ::close(fd);
    throw Error(std::string("run_command: fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    int failure = 0;
    if (::chdir(cwd.c_str()) != 0 || null_fd < 0 || ::dup2(null_fd, 0) < 0 || ::dup2(out_fd, 1) < 0 ||
        ::dup2(err_fd, 2) < 0)
      failure = errno;
    if (failure == 0) {
      ::execv(program.c_str(), args.data());
      failure = errno;
    }
    ssize_t ignored = ::write(report[1], &failure, sizeof failure);
    (void)ignored;
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here: whichever runs first, the group exists before we may kill it
  ::close(out_fd);
  ::close(err_fd);
  ::close(report[1]);
  int failure = 0;
  const ssize_t got = ::read(report[0], &failure, sizeof failure);
  ::close(report[0]);
  int status = 0;
  if (got == static_cast<ssize_t>(sizeof failure)) {
    ::waitpid(pid, &status, 0);
    outcome.reason = "cannot run " + argv[0] + ": " + std::strerror(failure);
    return outcome;
  }
  outcome.started = true;
  // Poll: short sleeps first (most commands of a test end fast), then 50 ms.
  auto pause = std::chrono::milliseconds(1);
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) throw Error(std::string("run_command: waitpid: ") + std::strerror(errno));
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > timeout_s) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      outcome.timed_out = true;
      outcome.reason = "timed out after " + format_double(timeout_s) + " s (its process group was killed)";
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  ::kill(-pid, SIGKILL);  // anything it left behind in its group (ESRCH when nothing is)
  outcome.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!outcome.timed_out) {
    if (WIFEXITED(status)) outcome.exit_status = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) outcome.signal = WTERMSIG(status);
  }
  return outcome;
}

std::string describe_outcome(const CommandOutcome& o, const std::string& program) {
  if (!o.started) return o.reason;
  if (o.timed_out) return wall_timeout_reason(program + " " + o.reason);
  if (o.signal != 0) return program + " was killed by signal " + std::to_string(o.signal) + " (" + strsignal(o.signal) + ")";
  return program + " exited with status " + std::to_string(o.exit_status);
}

}  // namespace demcal
