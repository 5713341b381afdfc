#include "demcal/jobs/point_store.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/wall_timeout.hpp"
#include "demcal/dem/result_json.hpp"
#include "demcal/dem/lab_test.hpp"

namespace demcal::jobs {

using dem::SceneSet;
using dem::TestResult;
using dem::RunOptions;

using json = nlohmann::json;

namespace {

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ",") + s;
  return out;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string status_text(const json& r) {
  return r.at("status").get<std::string>() == "ok" ? std::string("ok") : "failed: " + r.value("reason", std::string());
}

}  // namespace

// A design column is a scene parameter, the coded copy of one (NAME_coded), or
// a declared blank column (blank*, null_column); anything else is a typo or a
// design made for another scene, and running it would silently use defaults.
std::vector<std::string> design_parameter_columns(const SceneSet& scene, const Table& design,
                                                  const std::string& design_path) {
  std::vector<std::string> columns;
  auto list = [&]() {
    std::string out;
    for (const auto& [name, p] : scene.parameters()) out += (out.empty() ? "" : ", ") + name;
    return out;
  };
  for (const std::string& name : design.names()) {
    if (scene.parameters().count(name)) {
      columns.push_back(name);
      continue;
    }
    const bool coded = ends_with(name, "_coded") && scene.parameters().count(name.substr(0, name.size() - 6));
    const bool blank = name.rfind("blank", 0) == 0 || name == "null_column";
    if (!coded && !blank)
      throw Error(design_path + ": column \"" + name + "\" is not a parameter of " + (scene.size() > 1 ? "the tests of " : "the scene ") + scene.origin() +
                  " (its parameters: " + list() + "; also allowed: run, NAME_coded, blank*, null_column)");
  }
  if (columns.empty())
    throw Error(design_path + ": no column is named after a scene parameter (scene parameters: " + list() + ")");
  // A design is a list of distinct points with a number in every cell. A value
  // outside the scene's bounds is not checked here: that point is recorded as
  // failed with its reason and the batch goes on.
  if (design.rows() == 0) throw Error(design_path + ": the design has no runs");
  std::set<int> runs;
  for (std::size_t row = 0; row < design.rows(); ++row) {
    const int run = design.run_ids()[row];
    if (!runs.insert(run).second) throw Error(design_path + ": run " + std::to_string(run) + " appears twice");
    for (const std::string& c : columns)
      if (!std::isfinite(design.at(row, c)))
        throw Error(design_path + ": run " + std::to_string(run) + ", column \"" + c + "\": " +
                    format_double(design.at(row, c)) + " is not a finite number");
  }
  return columns;
}

std::vector<PointSpec> design_points(const Table& design, const std::vector<std::string>& columns, int seeds,
                                     const std::string& points_dir, const std::string& scene_fingerprint,
                                     int first_seed) {
  std::vector<PointSpec> points;
  // A row that repeats an earlier one (a design's centre replicates) runs on
  // the next block of seeds, so replicates are other specimens and a fit gets
  // a pure error; rows that occur once keep seeds first..first+seeds-1.
  std::map<std::map<std::string, double>, int> occurrences;
  for (std::size_t row = 0; row < design.rows(); ++row) {
    std::map<std::string, double> values;
    for (const std::string& c : columns) values[c] = design.at(row, c);
    const int replicate = occurrences[values]++;
    const int first = first_seed + replicate * seeds;
    for (int s = first; s < first + seeds; ++s) {
      PointSpec p;
      p.run = design.run_ids()[row];
      p.seed = static_cast<std::uint64_t>(s);
      p.design = values;
      p.file = points_dir + "/run" + std::to_string(p.run) + "_seed" + std::to_string(p.seed) + ".json";
      p.scene_fingerprint = scene_fingerprint;
      points.push_back(p);
    }
  }
  return points;
}

bool read_point_file(const std::string& path, json& out) {
  std::ifstream in(path);
  if (!in) return false;
  try {
    in >> out;
    return out.is_object() && out.contains("status");
  } catch (const json::exception&) {
    return false;
  }
}

bool same_point(const json& stored, const PointSpec& p) {
  if (!stored.contains("seed") || stored.at("seed").get<std::uint64_t>() != p.seed) return false;
  if (stored.value("scene_fingerprint", std::string()) != p.scene_fingerprint) return false;
  if (!stored.contains("parameters")) return false;
  const json& parameters = stored.at("parameters");
  for (const auto& [name, value] : p.design)
    if (!parameters.contains(name) || !parameters.at(name).is_number() || parameters.at(name).get<double>() != value)
      return false;
  return true;
}

Stored stored_state(const PointSpec& point, json& out) {
  if (!read_point_file(point.file, out)) return Stored::none;
  if (!same_point(out, point)) return Stored::stale;
  if (out.value("status", std::string()) != "ok" && is_wall_timeout(out.value("reason", std::string())))
    return Stored::wall_timeout;
  return Stored::reused;
}

bool stored_result(const PointSpec& point, json& out) { return stored_state(point, out) == Stored::reused; }

json failed_point(const PointSpec& p, const std::string& reason) {
  json out;
  out["status"] = "failed";
  out["reason"] = reason;
  out["run"] = p.run;
  out["seed"] = p.seed;
  out["parameters"] = p.design;
  out["macro"] = json::object();
  out["scene_fingerprint"] = p.scene_fingerprint;
  return out;
}

json compute_point(const SceneSet& scene, const PointSpec& p, const std::string& cache_dir) {
  try {
    std::map<std::string, double> parameters = scene.resolve(p.design);
    RunOptions options;
    options.seed = p.seed;
    options.cache_dir = cache_dir;
    // Beside its result file: run1_seed2.json keeps the point, run1_seed2/ an external command's files.
    options.work_dir = p.file.size() > 5 && p.file.compare(p.file.size() - 5, 5, ".json") == 0
                           ? p.file.substr(0, p.file.size() - 5)
                           : p.file + ".work";
    json out = scene.run(parameters, options);
    out["run"] = p.run;
    out["scene_fingerprint"] = p.scene_fingerprint;
    return out;
  } catch (const std::exception& e) {
    return failed_point(p, e.what());
  }
}

void store_point(const PointSpec& point, const json& result) {
  write_file_atomically(point.file, result.dump() + "\n");
}

void report_failed_point(const PointSpec& point, const json& result) {
  if (result.value("status", std::string()) == "ok") return;
  log::warn("run " + std::to_string(point.run) + " seed " + std::to_string(point.seed) + " failed: " +
            result.value("reason", std::string("no reason recorded")));
}

void write_point_outputs(const std::vector<json>& results, const std::vector<std::string>& design_columns,
                         const OutputFiles& files) {
  std::set<std::string> macro_names;
  for (const json& r : results)
    for (auto it = r.at("macro").begin(); it != r.at("macro").end(); ++it) macro_names.insert(it.key());

  const std::string temporary = files.out_path + ".tmp." + std::to_string(::getpid());
  {
    h5::File file(temporary, h5::Mode::Truncate);
    h5::Group root = file.group("/points", true);
    root.set_attribute("scene", files.scene_path);
    root.set_attribute("design", files.design_path);
    root.set_attribute("design_columns", join(design_columns));
    root.set_attribute("shard", files.shard);
    root.set_attribute("design_points", static_cast<std::int64_t>(files.design_points));
    for (const json& r : results) {
      const std::string name = "/points/run" + std::to_string(r.at("run").get<int>()) + "_seed" +
                               std::to_string(r.at("seed").get<std::uint64_t>());
      h5::Group g = file.group(name, true);
      g.set_attribute("status", status_text(r));
      g.set_attribute("run", static_cast<std::int64_t>(r.at("run").get<int>()));
      g.set_attribute("seed", static_cast<std::int64_t>(r.at("seed").get<std::uint64_t>()));
      json without_curve = r;
      without_curve.erase("curve");
      g.set_attribute("result", without_curve.dump());
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
  if (std::rename(temporary.c_str(), files.out_path.c_str()) != 0)
    throw Error(files.out_path + ": cannot move the responses file into place");

  if (files.csv_path.empty()) return;
  std::ostringstream csv;
  csv << "run";
  for (const auto& c : design_columns) csv << ',' << c;
  csv << ",seed,status";
  for (const auto& m : macro_names) csv << ',' << m;
  csv << '\n';
  for (const json& r : results) {
    csv << r.at("run").get<int>();
    for (const auto& c : design_columns) csv << ',' << format_double(r.at("parameters").value(c, std::nan("")));
    std::string status = status_text(r);
    for (char& ch : status)
      if (ch == ',' || ch == '\n' || ch == '"') ch = ';';
    csv << ',' << r.at("seed").get<std::uint64_t>() << ',' << status;
    for (const auto& m : macro_names) {
      const json& v = r.at("macro");
      csv << ',' << (v.contains(m) && v.at(m).is_number() ? format_double(v.at(m).get<double>()) : std::string("nan"));
    }
    csv << '\n';
  }
  write_file_atomically(files.csv_path, csv.str());
}

void write_known_outputs(const std::vector<json>& results, const std::vector<bool>& known,
                         const std::vector<std::string>& design_columns, const OutputFiles& files) {
  std::vector<json> done;
  for (std::size_t i = 0; i < results.size(); ++i)
    if (known[i]) done.push_back(results[i]);
  write_point_outputs(done, design_columns, files);
}

std::vector<json> read_point_outputs(const std::string& out_path, OutputFiles& files,
                                     std::vector<std::string>& design_columns) {
  h5::File file(out_path, h5::Mode::ReadOnly);
  if (!file.exists("/points")) throw Error(out_path + ": no /points group (not a demcal-dem batch result)");
  h5::Group root = file.group("/points", false);
  files.out_path = out_path;
  files.scene_path = root.has_attribute("scene") ? root.string_attribute("scene") : "";
  files.design_path = root.has_attribute("design") ? root.string_attribute("design") : "";
  files.shard = root.has_attribute("shard") ? root.string_attribute("shard") : "1/1";
  files.design_points =
      root.has_attribute("design_points") ? static_cast<std::size_t>(root.integer_attribute("design_points")) : 0;
  if (!root.has_attribute("design_columns"))
    throw Error(out_path + ": written by an older demcal-dem without the full point results; rerun its batch");
  design_columns = split(root.string_attribute("design_columns"));
  std::vector<json> results;
  for (const std::string& child : root.children()) {
    h5::Group g = file.group("/points/" + child, false);
    if (!g.has_attribute("result"))
      throw Error(out_path + ": point " + child + " has no stored result; rerun its batch");
    json r = json::parse(g.string_attribute("result"));
    for (const std::string& dataset : g.children())
      if (dataset.rfind("curve_", 0) == 0) r["curve"][dataset.substr(6)] = g.read_doubles(dataset);
    results.push_back(std::move(r));
  }
  std::sort(results.begin(), results.end(), [](const json& a, const json& b) {
    return std::make_pair(a.at("run").get<int>(), a.at("seed").get<std::uint64_t>()) <
           std::make_pair(b.at("run").get<int>(), b.at("seed").get<std::uint64_t>());
  });
  return results;
}

}  // namespace demcal::jobs
