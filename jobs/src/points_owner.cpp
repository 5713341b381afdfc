#include "demcal/jobs/points_owner.hpp"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/log.hpp"

namespace demcal::jobs {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// JSON, but not named *.json: the point files beside it are, and readers count them.
std::string owner_file(const BatchOptions& options) { return options.out_path + ".points/scene.owner"; }

// A path compared as the file system means it (./a.json and a.json are one).
std::string normal(const std::string& path) {
  std::error_code error;
  const fs::path p = fs::weakly_canonical(path, error);
  return error ? path : p.string();
}

std::string refusal(const BatchOptions& options, const std::string& stored) {
  return options.out_path + ": holds the results of another scene (" + stored + "); give another --out, or add "
         "--move-aside to move them into a new folder beside it first";
}

// The scene file a responses file of an older version names, "" when none can be read.
std::string scene_named_in(const std::string& out_path) {
  if (!fs::exists(out_path)) return "";
  try {
    h5::File file(out_path, h5::Mode::ReadOnly);
    const h5::Group points = file.group("/points", false);
    return points.has_attribute("scene") ? points.string_attribute("scene") : "";
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace

void check_result_files(const dem::SceneSet& scene, const BatchOptions& options) {
  const std::string path = owner_file(options);
  std::ifstream in(path);
  if (in) {
    json stored;
    try {
      in >> stored;
    } catch (const json::exception&) {
      throw Error(path + ": not valid JSON (the record of which scene OUT belongs to); move OUT aside or repair it");
    }
    const std::string name = stored.value("name", std::string()), file = stored.value("scene", std::string("?"));
    // A scene without a name of its own ("scene", or "tests" for a list) is told apart by its file.
    const bool unnamed = name == "scene" || name == "tests";
    if (name != scene.name() || (unnamed && normal(file) != normal(options.scene_path)))
      throw Error(refusal(options, "scene \"" + name + "\" from " + file));
    return;
  }
  const std::string named = scene_named_in(options.out_path);
  if (!named.empty() && normal(named) != normal(options.scene_path))
    throw Error(refusal(options, "scene file " + named));
}

void record_result_files(const dem::SceneSet& scene, const BatchOptions& options) {
  const std::string path = owner_file(options);
  if (fs::exists(path)) return;  // checked to be this scene's
  write_file_atomically(path, json({{"name", scene.name()}, {"scene", options.scene_path},
                                    {"fingerprint", scene.fingerprint()}})
                                      .dump(2) +
                                  "\n");
}

std::string move_results_aside(const BatchOptions& options) {
  std::vector<std::string> present;
  for (const std::string& p : {options.out_path, options.out_path + ".points", options.csv_path})
    if (!p.empty() && fs::exists(p)) present.push_back(p);
  if (present.empty()) return "";
  std::string stem = options.out_path;
  if (stem.size() > 3 && stem.compare(stem.size() - 3, 3, ".h5") == 0) stem.resize(stem.size() - 3);
  std::string folder;
  for (int k = 1;; ++k) {
    folder = stem + ".moved-" + std::to_string(k);
    if (!fs::exists(folder)) break;
  }
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw Error(folder + ": cannot create the folder to move the old results into (" + error.message() + ")");
  for (const std::string& p : present) {
    fs::rename(p, fs::path(folder) / fs::path(p).filename(), error);
    if (error) throw Error(p + ": cannot move it into " + folder + " (" + error.message() + ")");
  }
  return folder;
}

}  // namespace demcal::jobs
