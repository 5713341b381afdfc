#pragma once
// Runs every point of a design (times several seeds) on a scene, several at
// once, and resumes after a crash without repeating finished points.
//
// Each finished point is written at once as its own JSON file (atomically)
// under <out>.points/; the HDF5 responses file and the CSV export are rebuilt
// from those files after every point, also atomically. A kill -9 therefore
// loses at most the points that were running; a rerun skips the rest.
#include <cstdint>
#include <string>

namespace demcal::dem {

struct BatchOptions {
  std::string scene_path;
  std::string design_path;      // CSV, or HDF5 with the group /design
  std::string out_path;         // responses, .h5
  std::string csv_path;         // flat export; empty: none
  std::string cache_dir;        // packed specimens
  int seeds = 1;                // seeds 1..K per design point
  int jobs = 1;                 // points at once (one process each)
  bool progress = true;
};

struct BatchSummary {
  std::size_t points = 0, skipped = 0, ok = 0, failed = 0;
  double wall_s = 0;
};

BatchSummary run_batch(const BatchOptions& options);

}  // namespace demcal::dem
