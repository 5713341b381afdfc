#include "demcal/dem/batch.hpp"

#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/core/table.hpp"
#include "demcal/dem/result_json.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/ucs_test.hpp"

namespace demcal::dem {
namespace {

using json = nlohmann::json;

struct Point {
  int run = 0;
  std::uint64_t seed = 1;
  std::map<std::string, double> design;  // the design's values of scene parameters
  std::string file;                      // its result file
};

// A stored result belongs to a point only if it was made with the same seed
// and the same design values: a changed design never reuses a stale result.
bool same_point(const json& stored, const Point& p) {
  if (!stored.contains("seed") || stored.at("seed").get<std::uint64_t>() != p.seed) return false;
  if (!stored.contains("parameters")) return false;
  const json& parameters = stored.at("parameters");
  for (const auto& [name, value] : p.design)
    if (!parameters.contains(name) || !parameters.at(name).is_number() || parameters.at(name).get<double>() != value)
      return false;
  return true;
}

bool file_exists(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

bool read_json(const std::string& path, json& out) {
  std::ifstream in(path);
  if (!in) return false;
  try {
    in >> out;
    return out.is_object() && out.contains("status");
  } catch (const json::exception&) {
    return false;
  }
}

json failed_point(const Point& p, const std::string& reason) {
  json out;
  out["status"] = "failed";
  out["reason"] = reason;
  out["run"] = p.run;
  out["seed"] = p.seed;
  out["parameters"] = p.design;
  out["macro"] = json::object();
  return out;
}

json point_json(const Point& p, const std::map<std::string, double>& parameters, const TestResult& r) {
  json out = result_json(r, parameters, p.seed);
  out["run"] = p.run;
  out["curve"] = curve_json(r);
  return out;
}

// Runs one point in this (child) process and stores its result file.
void run_point(const Scene& scene, const Point& p, const std::string& cache_dir) {
  json out;
  try {
    std::map<std::string, double> parameters = scene.resolve(p.design);
    RunOptions options;
    options.seed = p.seed;
    options.cache_dir = cache_dir;
    out = point_json(p, parameters, run_test(scene, parameters, options));
  } catch (const std::exception& e) {
    out = failed_point(p, e.what());
  }
  write_file_atomically(p.file, out.dump() + "\n");
}

// Rebuilds the HDF5 responses and the CSV export from the finished points.
void write_outputs(const std::vector<Point>& points, const std::vector<std::string>& design_columns,
                   const BatchOptions& options) {
  std::vector<json> done;
  for (const Point& p : points) {
    json result;
    if (read_json(p.file, result)) done.push_back(result);
  }
  std::set<std::string> macro_names;
  for (const json& r : done)
    for (auto it = r.at("macro").begin(); it != r.at("macro").end(); ++it) macro_names.insert(it.key());

  const std::string temporary = options.out_path + ".tmp." + std::to_string(::getpid());
  {
    h5::File file(temporary, h5::Mode::Truncate);
    h5::Group root = file.group("/points", true);
    root.set_attribute("scene", options.scene_path);
    root.set_attribute("design", options.design_path);
    for (const json& r : done) {
      const std::string name = "/points/run" + std::to_string(r.at("run").get<int>()) + "_seed" +
                               std::to_string(r.at("seed").get<std::uint64_t>());
      h5::Group g = file.group(name, true);
      g.set_attribute("status", r.at("status").get<std::string>() == "ok" ? std::string("ok")
                                                                          : "failed: " + r.value("reason", std::string()));
      g.set_attribute("run", static_cast<std::int64_t>(r.at("run").get<int>()));
      g.set_attribute("seed", static_cast<std::int64_t>(r.at("seed").get<std::uint64_t>()));
      h5::Group params = file.group(name + "/parameters", true);
      for (auto it = r.at("parameters").begin(); it != r.at("parameters").end(); ++it)
        params.set_attribute(it.key(), it.value().get<double>());
      h5::Group macro = file.group(name + "/macro", true);
      for (auto it = r.at("macro").begin(); it != r.at("macro").end(); ++it)
        if (it.value().is_number()) macro.set_attribute(it.key(), it.value().get<double>());
      if (r.contains("curve"))
        for (auto it = r.at("curve").begin(); it != r.at("curve").end(); ++it)
          g.write("curve_" + it.key(), it.value().get<std::vector<double>>());
    }
    file.flush();
  }
  if (std::rename(temporary.c_str(), options.out_path.c_str()) != 0)
    throw Error(options.out_path + ": cannot move the responses file into place");

  if (options.csv_path.empty()) return;
  std::ostringstream csv;
  csv << "run";
  for (const auto& c : design_columns) csv << ',' << c;
  csv << ",seed,status";
  for (const auto& m : macro_names) csv << ',' << m;
  csv << '\n';
  for (const json& r : done) {
    csv << r.at("run").get<int>();
    for (const auto& c : design_columns) csv << ',' << format_double(r.at("parameters").value(c, std::nan("")));
    std::string status = r.at("status").get<std::string>();
    if (status != "ok") {
      status = "failed: " + r.value("reason", std::string());
      for (char& ch : status)
        if (ch == ',' || ch == '\n' || ch == '"') ch = ';';
    }
    csv << ',' << r.at("seed").get<std::uint64_t>() << ',' << status;
    for (const auto& m : macro_names) {
      const json& v = r.at("macro");
      csv << ',' << (v.contains(m) && v.at(m).is_number() ? format_double(v.at(m).get<double>()) : std::string("nan"));
    }
    csv << '\n';
  }
  write_file_atomically(options.csv_path, csv.str());
}

// Runs work(i) for i in [0, n) in child processes, at most `jobs` at a time;
// done(i, status) runs in this process as each child ends. Children die with
// this process (a killed batch leaves no orphan writing results).
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
        work(next);
        ::_exit(0);
      }
      running[pid] = next++;
    }
    int status = 0;
    pid_t pid = ::waitpid(-1, &status, 0);
    auto it = running.find(pid);
    if (it == running.end()) continue;
    std::size_t index = it->second;
    running.erase(it);
    done(index, status);
  }
}

}  // namespace

BatchSummary run_batch(const BatchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.seeds < 1) throw Error("--seeds must be at least 1");
  if (options.jobs < 1) throw Error("--jobs must be at least 1");
  Scene scene = Scene::load(options.scene_path);
  Table design = Table::read(options.design_path, "/design");

  std::vector<std::string> design_columns;
  for (const std::string& name : design.names()) {
    if (scene.parameters().count(name)) {
      design_columns.push_back(name);
    } else if (!(name.size() > 6 && name.compare(name.size() - 6, 6, "_coded") == 0) && name.rfind("blank", 0) != 0) {
      log::warn(options.design_path + ": column \"" + name + "\" is not a parameter of the scene; ignored");
    }
  }
  if (design_columns.empty()) {
    std::string list;
    for (const auto& [name, p] : scene.parameters()) list += (list.empty() ? "" : ", ") + name;
    throw Error(options.design_path + ": no column is named after a scene parameter (scene parameters: " + list + ")");
  }

  const std::string points_dir = options.out_path + ".points";
  ::mkdir(points_dir.c_str(), 0755);
  if (!file_exists(points_dir)) throw Error(points_dir + ": cannot create the folder of point results");
  std::vector<Point> points;
  for (std::size_t row = 0; row < design.rows(); ++row)
    for (int s = 1; s <= options.seeds; ++s) {
      Point p;
      p.run = design.run_ids()[row];
      p.seed = static_cast<std::uint64_t>(s);
      for (const std::string& c : design_columns) p.design[c] = design.at(row, c);
      p.file = points_dir + "/run" + std::to_string(p.run) + "_seed" + std::to_string(p.seed) + ".json";
      points.push_back(p);
    }

  BatchSummary summary;
  summary.points = points.size();
  std::vector<const Point*> pending;
  std::size_t stale = 0;
  for (const Point& p : points) {
    json existing;
    if (read_json(p.file, existing) && same_point(existing, p)) {
      ++summary.skipped;
    } else {
      if (file_exists(p.file)) ++stale;
      pending.push_back(&p);
    }
  }
  if (stale > 0)
    log::warn(std::to_string(stale) + " stored point(s) were made with other parameter values than the design now "
              "gives them; running them again");
  if (summary.skipped > 0)
    log::info("resuming: " + std::to_string(summary.skipped) + " of " + std::to_string(points.size()) +
              " points already done");

  // Pack each distinct specimen once (in parallel), before the points share it.
  std::vector<SpecimenSpec> to_pack;
  std::set<std::string> keys;
  for (const Point* p : pending) {
    try {
      SpecimenSpec spec = scene.specimen(scene.resolve(p->design), p->seed);
      if (keys.insert(spec.cache_key()).second) to_pack.push_back(spec);
    } catch (const Error&) {
      // The point itself will record why it cannot run.
    }
  }
  if (!to_pack.empty() && options.progress)
    log::info("packing " + std::to_string(to_pack.size()) + " specimen(s) (cached in " + options.cache_dir + ")");
  for_each_in_workers(
      to_pack.size(), options.jobs,
      [&](std::size_t i) {
        try {
          cached_specimen(to_pack[i], options.cache_dir);
        } catch (const std::exception&) {
          // Reported by the points that need this specimen.
        }
      },
      [](std::size_t, int) {});

  std::unique_ptr<Progress> progress;
  if (options.progress) {
    progress = std::make_unique<Progress>("points", pending.size(), 10.0);
    progress->set_units_name("particle-steps");
  }
  for_each_in_workers(
      pending.size(), options.jobs, [&](std::size_t i) { run_point(scene, *pending[i], options.cache_dir); },
      [&](std::size_t i, int status) {
        const Point* p = pending[i];
        json result;
        if (!read_json(p->file, result)) {
          std::string reason = WIFSIGNALED(status) ? "crashed (signal " + std::to_string(WTERMSIG(status)) + ")"
                                                   : "exited without a result (status " +
                                                         std::to_string(WEXITSTATUS(status)) + ")";
          result = failed_point(*p, reason);
          write_file_atomically(p->file, result.dump() + "\n");
        }
        write_outputs(points, design_columns, options);
        if (progress) progress->advance(1, result.value("particles", 0.0) * result.value("steps", 0.0));
      });
  write_outputs(points, design_columns, options);
  for (const Point& p : points) {
    json r;
    if (read_json(p.file, r)) (r.at("status") == "ok" ? summary.ok : summary.failed)++;
  }
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace demcal::dem
