#pragma once
// Runs work(i) for i in [0, n) in child processes, at most `jobs` at a time;
// done(i, status) runs in this process as each child ends. Children die with
// this process (a killed batch leaves no orphan writing results), and a child
// that crashes takes only its own point with it.
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <map>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"

namespace demcal::jobs {

template <typename Work, typename Done>
void for_each_in_workers(std::size_t n, int jobs, Work work, Done done) {
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  while (next < n || !running.empty()) {
    while (next < n && static_cast<int>(running.size()) < jobs) {
      std::fflush(nullptr);
      pid_t pid = ::fork();
      if (pid < 0) throw Error("cannot start a worker process");
      if (pid == 0) {
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        log::set_level(log::Level::Quiet);
        // Never unwind into the parent's code (its destructors, its catch blocks).
        try {
          work(next);
        } catch (...) {
          ::_exit(1);
        }
        ::_exit(0);
      }
      running[pid] = next++;
    }
    int status = 0;
    pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw Error("lost track of the worker processes (waitpid failed)");
    }
    auto it = running.find(pid);
    if (it == running.end()) continue;
    std::size_t index = it->second;
    running.erase(it);
    done(index, status);
  }
}

// Why a child ended without leaving its result.
inline std::string worker_end_reason(int status) {
  return WIFSIGNALED(status) ? "crashed (signal " + std::to_string(WTERMSIG(status)) + ")"
                             : "exited without a result (status " + std::to_string(WEXITSTATUS(status)) + ")";
}

}  // namespace demcal::jobs
