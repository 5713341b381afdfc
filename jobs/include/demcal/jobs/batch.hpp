#pragma once
// Runs every point of a design (times several seeds) on a scene, several at
// once, and resumes after a crash without repeating finished points.
//
// Each finished point is written at once as its own JSON file (atomically)
// under <out>.points/; the HDF5 responses file and the CSV export are rebuilt
// from those files after every point, also atomically. A kill -9 therefore
// loses at most the points that were running; a rerun skips the rest.
//
// A shard (--shard i/N) runs every N-th point only, for the job arrays of a
// cluster scheduler; demcal-dem merge joins the shards' result files.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/jobs/point_store.hpp"
#include "demcal/dem/scene_set.hpp"

namespace demcal::jobs {

struct BatchOptions {
  std::string scene_path;
  std::string design_path;      // CSV, or HDF5 with the group /design
  std::string out_path;         // responses, .h5
  std::string csv_path;         // flat export; empty: none
  std::string cache_dir;        // packed specimens
  int seeds = 1;                // seeds per design point (first_seed .. first_seed + K - 1)
  int first_seed = 1;
  int jobs = 1;                 // points at once (one process each)
  int threads = 0;              // threads shared by the points at once (0: OpenMP's default, every core)
  int shard_index = 1;          // this shard, 1..shard_count
  int shard_count = 1;
  bool progress = true;
  // OUT holds another scene's results: move them into OUT_STEM.moved-K/ and
  // start afresh, instead of refusing (points_owner.hpp).
  bool move_aside = false;
};

struct BatchSummary {
  std::size_t points = 0, skipped = 0, ok = 0, failed = 0;
  double wall_s = 0;
};

// Parses "i/N" (1 <= i <= N) into the options; throws a one-line error.
void parse_shard(const std::string& text, BatchOptions& options);

// The points of the batch (this shard's only), with their result files.
// `design_total` receives the point count of the whole design (all shards).
// `make_folder` false: do not create OUT.points/ (an MPI worker may not share rank 0's disk).
std::vector<PointSpec> batch_points(const dem::SceneSet& scene, const BatchOptions& options,
                                    std::vector<std::string>& design_columns, std::size_t* design_total = nullptr,
                                    bool make_folder = true);

// The distinct specimens the points need, in the points' order (points that
// cannot run are skipped: they record why themselves).
std::vector<dem::SpecimenToPack> distinct_specimens(const dem::SceneSet& scene, const std::vector<const PointSpec*>& points);

// The result files of a batch: its shard ("i/N") and the whole design's point count recorded.
OutputFiles batch_output_files(const BatchOptions& options, std::size_t design_total);

BatchSummary run_batch(const BatchOptions& options);

struct PointRunOptions {
  int jobs = 1;
  // Threads the points running at once share (0: OpenMP's default, i.e.
  // OMP_NUM_THREADS or every core): each gets threads / min(jobs, points), at
  // least one, so fewer points than cores still use every core.
  int threads = 0;
  std::string cache_dir;
  bool progress = true;
  std::string progress_label = "points";
};

// Threads for each of `tasks` runs when at most `jobs` run at once: the
// budget `threads` (0: OpenMP's default) split between the runs that can be
// running together, at least one each.
int threads_per_run(int threads, int jobs, std::size_t tasks);

// Runs the points that have no stored result of their own (at most `jobs`
// at once, one process each, specimens packed once beforehand), stores each
// result as it finishes and calls on_done(point index, result). Returns every
// point's result, stored or new, in the order given.
std::vector<nlohmann::json> run_points(const dem::SceneSet& scene, const std::vector<PointSpec>& points,
                                       const PointRunOptions& options,
                                       const std::function<void(std::size_t, const nlohmann::json&)>& on_done = {},
                                       std::size_t* skipped = nullptr);

}  // namespace demcal::jobs
