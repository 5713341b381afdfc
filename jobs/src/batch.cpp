#include "demcal/jobs/batch.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <set>

#include <omp.h>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/jobs/points_owner.hpp"
#include "worker_pool.hpp"

namespace demcal::jobs {

using dem::SceneSet;

using json = nlohmann::json;

namespace {

bool file_exists(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

// Packs each distinct specimen of the points once (in parallel), before the
// points share it through the cache.
void pack_specimens(const SceneSet& scene, const std::vector<const PointSpec*>& pending, const PointRunOptions& options) {
  const std::vector<dem::SpecimenToPack> to_pack = distinct_specimens(scene, pending);
  if (to_pack.empty() || options.cache_dir.empty()) return;
  if (options.progress)
    log::info("packing " + std::to_string(to_pack.size()) + " specimen(s) (cached in " + options.cache_dir + ")");
  const int threads = threads_per_run(options.threads, options.jobs, to_pack.size());
  for_each_in_workers(
      to_pack.size(), options.jobs,
      [&](std::size_t i) {
        omp_set_num_threads(threads);
        try {
          to_pack[i].pack(options.cache_dir);
        } catch (const std::exception&) {
          // Reported by the points that need this specimen.
        }
      },
      [](std::size_t, int) {});
}

}  // namespace

int threads_per_run(int threads, int jobs, std::size_t tasks) {
  const int budget = threads > 0 ? threads : omp_get_max_threads();
  const std::size_t at_once = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(jobs), tasks));
  return std::max(1, budget / static_cast<int>(at_once));
}

std::vector<dem::SpecimenToPack> distinct_specimens(const SceneSet& scene, const std::vector<const PointSpec*>& points) {
  std::vector<dem::SpecimenToPack> specimens;
  std::set<std::string> keys;
  for (const PointSpec* p : points) {
    try {
      for (dem::SpecimenToPack& spec : scene.specimens(scene.resolve(p->design), p->seed))
        if (keys.insert(spec.cache_key).second) specimens.push_back(std::move(spec));
    } catch (const Error&) {
      // The point itself will record why it cannot run.
    }
  }
  return specimens;
}

void parse_shard(const std::string& text, BatchOptions& options) {
  const auto slash = text.find('/');
  int index = 0, count = 0;
  try {
    std::size_t used_index = 0, used_count = 0;
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    index = std::stoi(text.substr(0, slash), &used_index);
    count = std::stoi(text.substr(slash + 1), &used_count);
    if (used_index != slash || used_count != text.size() - slash - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw Error("--shard \"" + text + "\": expected I/N, e.g. 2/8");
  }
  if (count < 1 || index < 1 || index > count)
    throw Error("--shard " + text + ": I must be between 1 and N (N >= 1)");
  options.shard_index = index;
  options.shard_count = count;
}

OutputFiles batch_output_files(const BatchOptions& options, std::size_t design_total) {
  OutputFiles files{options.out_path, options.csv_path, options.scene_path, options.design_path};
  files.shard = std::to_string(options.shard_index) + "/" + std::to_string(options.shard_count);
  files.design_points = design_total;
  return files;
}

std::vector<PointSpec> batch_points(const SceneSet& scene, const BatchOptions& options,
                                    std::vector<std::string>& design_columns, std::size_t* design_total,
                                    bool make_folder) {
  if (options.seeds < 1) throw Error("--seeds must be at least 1");
  if (options.first_seed < 1) throw Error("--first-seed must be at least 1");
  Table design = Table::read(options.design_path, "/design");
  design_columns = design_parameter_columns(scene, design, options.design_path);
  const std::string points_dir = options.out_path + ".points";
  if (make_folder) {
    if (options.move_aside) {
      try {
        check_result_files(scene, options);
      } catch (const Error&) {
        log::info("moved the results of another scene to " + move_results_aside(options));
      }
    }
    check_result_files(scene, options);  // before the folder is made or anything written
    ::mkdir(points_dir.c_str(), 0755);
    if (!file_exists(points_dir)) throw Error(points_dir + ": cannot create the folder of point results");
    record_result_files(scene, options);
  }
  std::vector<PointSpec> all = design_points(design, design_columns, options.seeds, points_dir, scene.fingerprint(),
                                             options.first_seed);
  if (design_total) *design_total = all.size();
  if (options.shard_count == 1) return all;
  // Every N-th point (rows and seeds interleaved), so shards get alike mixes.
  std::vector<PointSpec> shard;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (static_cast<int>(i % options.shard_count) == options.shard_index - 1) shard.push_back(all[i]);
  return shard;
}

std::vector<json> run_points(const SceneSet& scene, const std::vector<PointSpec>& points, const PointRunOptions& options,
                             const std::function<void(std::size_t, const json&)>& on_done, std::size_t* skipped) {
  if (options.jobs < 1) throw Error("--jobs must be at least 1");
  std::vector<json> results(points.size());
  std::vector<std::size_t> pending;
  std::size_t stale = 0, timed_out = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Stored stored = stored_state(points[i], results[i]);
    if (stored == Stored::reused) continue;
    stale += stored == Stored::stale || (stored == Stored::none && file_exists(points[i].file));  // unreadable
    timed_out += stored == Stored::wall_timeout;
    pending.push_back(i);
  }
  if (skipped) *skipped = points.size() - pending.size();
  if (stale > 0)
    log::warn(std::to_string(stale) + " stored point(s) were made with other parameter values, another scene or an older engine; "
              "running them again");
  if (timed_out > 0)
    log::warn(std::to_string(timed_out) + " stored point(s) failed at a wall-clock limit, which the machine's load decides; "
              "running them again");
  if (pending.empty()) return results;

  std::vector<const PointSpec*> pending_points;
  for (std::size_t i : pending) pending_points.push_back(&points[i]);
  pack_specimens(scene, pending_points, options);

  std::unique_ptr<Progress> progress;
  if (options.progress) {
    progress = std::make_unique<Progress>(options.progress_label, pending.size(), 10.0);
    progress->set_units_name("particle-steps");
  }
  // Fewer points than jobs (a verification over a few seeds): each gets more threads.
  const int threads = threads_per_run(options.threads, options.jobs, pending.size());
  for_each_in_workers(
      pending.size(), options.jobs,
      [&](std::size_t k) {
        omp_set_num_threads(threads);
        const PointSpec& p = points[pending[k]];
        store_point(p, compute_point(scene, p, options.cache_dir));
      },
      [&](std::size_t k, int status) {
        const std::size_t i = pending[k];
        json& result = results[i];
        if (!read_point_file(points[i].file, result) || !same_point(result, points[i])) {
          result = failed_point(points[i], worker_end_reason(status));
          store_point(points[i], result);
        }
        report_failed_point(points[i], result);
        if (on_done) on_done(i, result);
        if (progress) progress->advance(1, result.value("particles", 0.0) * result.value("steps", 0.0));
      });
  return results;
}

BatchSummary run_batch(const BatchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.jobs < 1) throw Error("--jobs must be at least 1");
  SceneSet scene = SceneSet::load(options.scene_path);
  std::vector<std::string> design_columns;
  std::size_t design_total = 0;
  std::vector<PointSpec> points = batch_points(scene, options, design_columns, &design_total);
  const OutputFiles files = batch_output_files(options, design_total);

  // What is stored now, so the outputs can be rebuilt after every point.
  std::vector<json> known(points.size());
  std::vector<bool> have(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) have[i] = stored_result(points[i], known[i]);
  auto write_outputs = [&]() { write_known_outputs(known, have, design_columns, files); };

  BatchSummary summary;
  summary.points = points.size();
  for (bool h : have) summary.skipped += h ? 1 : 0;
  if (summary.skipped > 0)
    log::info("resuming: " + std::to_string(summary.skipped) + " of " + std::to_string(points.size()) +
              " points already done");
  PointRunOptions run_options;
  run_options.jobs = options.jobs;
  run_options.threads = options.threads;
  run_options.cache_dir = options.cache_dir;
  run_options.progress = options.progress;
  std::vector<json> results = run_points(scene, points, run_options, [&](std::size_t i, const json& result) {
    known[i] = result;
    have[i] = true;
    write_outputs();
  });
  write_outputs();
  for (const json& r : results) (r.at("status") == "ok" ? summary.ok : summary.failed)++;
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace demcal::jobs
