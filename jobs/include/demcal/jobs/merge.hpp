#pragma once
// Joins the result files of batch shards (demcal-dem batch --shard i/N, e.g.
// one per task of a cluster job array) into one responses file, with its
// CSV and its folder of point results, so a later batch over the whole
// design resumes from it and runs only what no shard finished.
#include <string>
#include <vector>

namespace demcal::jobs {

struct MergeSummary {
  std::size_t inputs = 0, points = 0, duplicates = 0, failed = 0;
  std::size_t design_points = 0;  // of the whole design: more than `points` when shards are missing
};

// Throws when the inputs come from different scenes, designs or design
// columns, or when two inputs hold different results for the same run and
// seed. Missing points (a shard not given, or not finished) are reported in
// the summary, not an error: a batch over the whole design fills them in.
MergeSummary merge_results(const std::vector<std::string>& inputs, const std::string& out_path,
                           const std::string& csv_path);

}  // namespace demcal::jobs
