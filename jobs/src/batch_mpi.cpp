#include "demcal/jobs/batch_mpi.hpp"

#include <mpi.h>
#include <omp.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <set>
#include <thread>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/dem/lab_test.hpp"
#include "worker_pool.hpp"

namespace demcal::jobs {

using dem::SceneSet;
using dem::SpecimenToPack;

using json = nlohmann::json;

namespace {

enum Tag : int { kTask = 1, kResult = 2 };
enum TaskKind : int { kStop = 0, kPack = 1, kRun = 2 };

// Runs `work` in a child process and returns what it wrote to the pipe; empty
// when the child died first (its status in `status`).
template <typename Work>
std::string in_child(Work work, int& status) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error("cannot create a pipe to a worker process");
  std::fflush(nullptr);
  pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error("cannot start a worker process");
  }
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // dies with its rank (MPI_Abort, a cancelled job)
    ::close(fds[0]);
    std::string text;
    try {  // never unwind into the rank's code (MPI calls, its catch blocks)
      text = work();
    } catch (...) {
      ::_exit(1);
    }
    std::size_t written = 0;
    while (written < text.size()) {
      ssize_t n = ::write(fds[1], text.data() + written, text.size() - written);
      if (n <= 0) ::_exit(1);
      written += static_cast<std::size_t>(n);
    }
    ::close(fds[1]);
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string text;
  char buffer[65536];
  for (;;) {
    ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) text.clear();
  return text;
}

void send_task(int rank, int kind, int index) {
  int task[2] = {kind, index};
  MPI_Send(task, 2, MPI_INT, rank, kTask, MPI_COMM_WORLD);
}

// Waits (without spinning a core: rank 0 shares the machine with workers)
// for the next result message; returns its source and text.
std::pair<int, std::string> receive_result() {
  MPI_Status status;
  int flag = 0;
  for (;;) {
    MPI_Iprobe(MPI_ANY_SOURCE, kResult, MPI_COMM_WORLD, &flag, &status);
    if (flag) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  int length = 0;
  MPI_Get_count(&status, MPI_CHAR, &length);
  std::string text(static_cast<std::size_t>(length), '\0');
  MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return {status.MPI_SOURCE, text};
}

void send_result(const std::string& text) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kResult, MPI_COMM_WORLD);
}

struct Setup {
  SceneSet scene;
  std::vector<std::string> design_columns;
  std::vector<PointSpec> points;
  std::vector<SpecimenToPack> to_pack;
  std::size_t design_total = 0;
};

Setup set_up(const BatchOptions& options, bool master) {
  Setup s{SceneSet::load(options.scene_path), {}, {}, {}};
  // The same points on every rank; only rank 0 writes, so only it makes the folder.
  s.points = batch_points(s.scene, options, s.design_columns, &s.design_total, master);
  return s;
}

void worker(const BatchOptions& options, const Setup& s) {
  // Ranks usually share a node one per core: one thread each unless asked
  // (--threads, the threads of each rank's runs).
  omp_set_num_threads(options.threads > 0 ? options.threads : 1);
  for (;;) {
    int task[2];
    MPI_Recv(task, 2, MPI_INT, 0, kTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (task[0] == kStop) return;
    int status = 0;
    if (task[0] == kPack) {
      const SpecimenToPack& spec = s.to_pack.at(static_cast<std::size_t>(task[1]));
      in_child(
          [&]() {
            try {
              spec.pack(options.cache_dir);
            } catch (const std::exception&) {
              // Reported by the points that need this specimen.
            }
            return std::string("packed");
          },
          status);
      send_result("packed");
      continue;
    }
    const PointSpec& p = s.points.at(static_cast<std::size_t>(task[1]));
    std::string text = in_child([&]() { return compute_point(s.scene, p, options.cache_dir).dump(); }, status);
    if (text.empty()) text = failed_point(p, worker_end_reason(status)).dump();
    send_result(text);
  }
}

// Hands out `count` tasks of one kind to the workers, one each at a time.
void distribute(int workers, int kind, std::size_t count, const std::function<int(std::size_t)>& index_of,
                const std::function<void(std::size_t, const std::string&)>& on_result) {
  std::vector<long> assigned(static_cast<std::size_t>(workers) + 1, -1);
  std::size_t next = 0, active = 0;
  for (int r = 1; r <= workers && next < count; ++r, ++next, ++active) {
    send_task(r, kind, index_of(next));
    assigned[static_cast<std::size_t>(r)] = static_cast<long>(next);
  }
  while (active > 0) {
    auto [rank, text] = receive_result();
    const std::size_t done = static_cast<std::size_t>(assigned[static_cast<std::size_t>(rank)]);
    --active;
    if (next < count) {
      send_task(rank, kind, index_of(next));
      assigned[static_cast<std::size_t>(rank)] = static_cast<long>(next++);
      ++active;
    }
    on_result(done, text);
  }
}

}  // namespace

bool started_by_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SINGLE, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

BatchSummary run_batch_mpi(const BatchOptions& options, const MpiSession& mpi) {
  const auto start = std::chrono::steady_clock::now();
  const bool master = mpi.rank() == 0;
  Setup s;
  std::string setup_error;
  try {
    s = set_up(options, master);
  } catch (const std::exception& e) {
    setup_error = e.what();
  }
  // Every rank learns whether any rank failed to set up, so none is left
  // waiting, and whether rank 0 did: then rank 0 alone says why (one line);
  // a worker prints its own error only when rank 0 had none (e.g. a file
  // missing on that worker's node). Workers then end normally so that the
  // launcher does not abort the job before rank 0 has printed.
  int local_ok = setup_error.empty() ? 1 : 0, all_ok = 0, master_ok = local_ok;
  MPI_Allreduce(&local_ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  MPI_Bcast(&master_ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!all_ok) {
    if (master) throw Error(setup_error.empty() ? "a worker rank could not read the scene or the design" : setup_error);
    if (master_ok && !setup_error.empty()) std::fprintf(stderr, "demcal-dem: rank %d: %s\n", mpi.rank(), setup_error.c_str());
    return {};
  }

  // Rank 0 decides what runs; the workers learn it through the task indices.
  std::vector<std::size_t> pending;
  std::vector<json> known(s.points.size());
  std::vector<bool> have(s.points.size(), false);
  BatchSummary summary;
  if (master) {
    for (std::size_t i = 0; i < s.points.size(); ++i)
      if (stored_result(s.points[i], known[i])) have[i] = true;
      else pending.push_back(i);
  }
  unsigned long long pending_count = pending.size();
  MPI_Bcast(&pending_count, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  std::vector<unsigned long long> pending_wire(pending.begin(), pending.end());
  pending_wire.resize(pending_count);
  MPI_Bcast(pending_wire.data(), static_cast<int>(pending_count), MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  pending.assign(pending_wire.begin(), pending_wire.end());
  // The distinct specimens in an order every rank agrees on (pack tasks are indices into it).
  std::vector<const PointSpec*> pending_points;
  for (std::size_t i : pending) pending_points.push_back(&s.points[i]);
  s.to_pack = distinct_specimens(s.scene, pending_points);

  if (!master) {
    try {
      worker(options, s);
    } catch (const std::exception& e) {
      log::set_level(log::Level::Normal);
      log::error("rank " + std::to_string(mpi.rank()) + ": " + e.what());
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    return {};
  }

  try {
    const int workers = mpi.size() - 1;
    summary.points = s.points.size();
    summary.skipped = s.points.size() - pending.size();
    if (options.jobs > 1) log::warn("--jobs is ignored under MPI: each worker rank runs one point at a time");
    if (summary.skipped > 0)
      log::info("resuming: " + std::to_string(summary.skipped) + " of " + std::to_string(s.points.size()) +
                " points already done");
    log::info(std::to_string(pending.size()) + " point(s) over " + std::to_string(workers) + " worker rank(s)");
    const OutputFiles files = batch_output_files(options, s.design_total);
    auto write_outputs = [&]() { write_known_outputs(known, have, s.design_columns, files); };

    if (!s.to_pack.empty() && !options.cache_dir.empty()) {
      if (options.progress)
        log::info("packing " + std::to_string(s.to_pack.size()) + " specimen(s) (cached in " + options.cache_dir + ")");
      distribute(workers, kPack, s.to_pack.size(), [](std::size_t k) { return static_cast<int>(k); },
                 [](std::size_t, const std::string&) {});
    }
    std::unique_ptr<Progress> progress;
    if (options.progress) {
      progress = std::make_unique<Progress>("points", pending.size(), 10.0);
      progress->set_units_name("particle-steps");
    }
    distribute(workers, kRun, pending.size(), [&](std::size_t k) { return static_cast<int>(pending[k]); },
               [&](std::size_t k, const std::string& text) {
                 const std::size_t i = pending[k];
                 json result;
                 try {
                   result = json::parse(text);
                 } catch (const json::exception&) {
                   result = failed_point(s.points[i], "unreadable result from a worker rank");
                 }
                 store_point(s.points[i], result);
                 report_failed_point(s.points[i], result);
                 known[i] = result;
                 have[i] = true;
                 write_outputs();
                 if (progress) progress->advance(1, result.value("particles", 0.0) * result.value("steps", 0.0));
               });
    for (int r = 1; r <= workers; ++r) send_task(r, kStop, 0);
    write_outputs();
    for (std::size_t i = 0; i < s.points.size(); ++i) (known[i].at("status") == "ok" ? summary.ok : summary.failed)++;
  } catch (const std::exception& e) {
    log::error(e.what());
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace demcal::jobs
