#pragma once
// The results of design points, one JSON file per (run, seed), and the two
// files rebuilt from them (the HDF5 responses and the flat CSV). Shared by
// the process-parallel batch, the MPI batch, shards and their merge, and the
// DEM-in-the-loop model, so every way of running points stores them alike.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/core/table.hpp"
#include "demcal/dem/scene_set.hpp"

namespace demcal::jobs {

struct PointSpec {
  int run = 0;
  std::uint64_t seed = 1;
  std::map<std::string, double> design;  // the design's values of scene parameters
  std::string file;                      // its result file
  std::string scene_fingerprint;         // Scene::fingerprint() of the scene it runs on
};

// The design's columns that are scene parameters. Throws a one-line error
// naming the file for any other column (but NAME_coded and blank columns), a
// design without runs, a run id twice, or a cell that is not a finite number.
std::vector<std::string> design_parameter_columns(const dem::SceneSet& scene, const Table& design,
                                                  const std::string& design_path);

// Every (row, seed first_seed .. first_seed + seeds - 1) of the design, in row
// order then seed order, with result files under points_dir. The k-th repeat
// of an identical row (k = 1, 2, ...) takes seeds first_seed + k * seeds
// onwards instead: replicates are distinct specimens.
std::vector<PointSpec> design_points(const Table& design, const std::vector<std::string>& columns, int seeds,
                                     const std::string& points_dir, const std::string& scene_fingerprint,
                                     int first_seed = 1);

// Reads a stored result; false when the file is missing or not a result.
bool read_point_file(const std::string& path, nlohmann::json& out);
// A stored result belongs to a point only if it was made with the same seed,
// the same design values and the same scene (content and results version): a
// changed design, an edited scene or a newer engine never reuses a stale result.
bool same_point(const nlohmann::json& stored, const PointSpec& point);
// What is stored for `point`: nothing, its result (reused), a stale one
// (other values, scene or engine) or a failure by a wall-clock limit, which
// the machine's load decided and which is therefore run again (out holds what
// was read in every case but `none`).
enum class Stored { none, reused, stale, wall_timeout };
Stored stored_state(const PointSpec& point, nlohmann::json& out);
// The stored result of `point`, when there is one made with its values (a
// wall-clock timeout is not kept).
bool stored_result(const PointSpec& point, nlohmann::json& out);

// Runs one point in this process (never throws: a failure is a failed result).
nlohmann::json compute_point(const dem::SceneSet& scene, const PointSpec& point, const std::string& cache_dir);
nlohmann::json failed_point(const PointSpec& point, const std::string& reason);
void store_point(const PointSpec& point, const nlohmann::json& result);
// Says on stderr, as it happens, that a point failed and why (nothing for a point that is ok).
void report_failed_point(const PointSpec& point, const nlohmann::json& result);

struct OutputFiles {
  std::string out_path;     // responses .h5
  std::string csv_path;     // flat CSV; empty: none
  std::string scene_path;   // recorded as attributes
  std::string design_path;
  std::string shard = "1/1";        // which part of the design this file holds
  std::size_t design_points = 0;    // points of the whole design (all shards)
};

// Rewrites the responses file and the CSV (atomically) from the results, in
// the order given. Each HDF5 point group keeps its whole result as the JSON
// attribute "result" besides the macro values and the curve, so shards merge
// without loss.
void write_point_outputs(const std::vector<nlohmann::json>& results, const std::vector<std::string>& design_columns,
                         const OutputFiles& files);

// The same from the results known so far: results[i] where known[i] (a batch
// calls it after every point, the rest still running or to come).
void write_known_outputs(const std::vector<nlohmann::json>& results, const std::vector<bool>& known,
                         const std::vector<std::string>& design_columns, const OutputFiles& files);

// Reads the point results back from a responses file written above.
std::vector<nlohmann::json> read_point_outputs(const std::string& out_path, OutputFiles& files,
                                               std::vector<std::string>& design_columns);

}  // namespace demcal::jobs
