#include "demcal/jobs/merge.hpp"

#include <sys/stat.h>

#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/jobs/point_store.hpp"

namespace demcal::jobs {

using json = nlohmann::json;

MergeSummary merge_results(const std::vector<std::string>& inputs, const std::string& out_path,
                           const std::string& csv_path) {
  if (inputs.empty()) throw Error("merge: no input result files");
  MergeSummary summary;
  std::string scene, design;
  std::vector<std::string> columns;
  std::size_t design_points = 0;
  std::set<std::string> shards;
  std::map<std::pair<int, std::uint64_t>, std::pair<json, std::string>> merged;  // (run, seed) -> result, file
  for (const std::string& input : inputs) {
    if (input == out_path) throw Error("merge: " + input + " is both an input and the output");
    OutputFiles in;
    std::vector<std::string> input_columns;
    std::vector<json> results = read_point_outputs(input, in, input_columns);
    if (summary.inputs == 0) {
      scene = in.scene_path;
      design = in.design_path;
      columns = input_columns;
      design_points = in.design_points;
    } else if (in.scene_path != scene) {
      throw Error("merge: " + input + " was run on scene " + in.scene_path + ", " + inputs.front() + " on " + scene);
    } else if (in.design_path != design || in.design_points != design_points) {
      throw Error("merge: " + input + " was run on design " + in.design_path + " (" + std::to_string(in.design_points) +
                  " points), " + inputs.front() + " on " + design + " (" + std::to_string(design_points) + ")");
    } else if (input_columns != columns) {
      throw Error("merge: " + input + " has other design columns than " + inputs.front());
    }
    shards.insert(in.shard);
    ++summary.inputs;
    for (json& r : results) {
      const auto key = std::make_pair(r.at("run").get<int>(), r.at("seed").get<std::uint64_t>());
      auto it = merged.find(key);
      if (it == merged.end()) {
        merged.emplace(key, std::make_pair(std::move(r), input));
        continue;
      }
      const json& kept = it->second.first;
      if (kept.at("parameters") != r.at("parameters") || kept.at("macro") != r.at("macro") ||
          kept.at("status") != r.at("status"))
        throw Error("merge: run " + std::to_string(key.first) + " seed " + std::to_string(key.second) +
                    " differs between " + it->second.second + " and " + input);
      ++summary.duplicates;
    }
  }

  const std::string points_dir = out_path + ".points";
  ::mkdir(points_dir.c_str(), 0755);
  std::vector<json> results;
  for (auto& [key, entry] : merged) {
    PointSpec point;
    point.file = points_dir + "/run" + std::to_string(key.first) + "_seed" + std::to_string(key.second) + ".json";
    store_point(point, entry.first);
    if (entry.first.at("status") != "ok") ++summary.failed;
    results.push_back(std::move(entry.first));
  }
  OutputFiles files{out_path, csv_path, scene, design};
  files.design_points = design_points;
  write_point_outputs(results, columns, files);
  summary.points = results.size();
  summary.design_points = design_points;
  return summary;
}

}  // namespace demcal::jobs
