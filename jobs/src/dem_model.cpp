#include "demcal/jobs/dem_model.hpp"

#include <set>

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/output_ratio.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/jobs/batch.hpp"
#include "demcal/jobs/point_store.hpp"

namespace demcal::jobs {

using dem::SceneSet;

using json = nlohmann::json;

namespace {

std::vector<InputRange> space_domain(const ParameterSpace& space) {
  std::vector<InputRange> domain;
  for (const Parameter& p : space.parameters()) domain.push_back({p.name, p.low, p.high});
  return domain;
}

void make_folder(const std::string& path) {
  ::mkdir(path.c_str(), 0755);
  struct stat info;
  if (::stat(path.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) throw Error(path + ": cannot create the folder");
}

}  // namespace

DemModel::DemModel(const std::string& scene_path, const ParameterSpace& space, std::vector<std::string> outputs,
                   DemModelOptions options)
    : BoxModel(space_domain(space), std::move(outputs)),
      scene_path_(scene_path),
      scene_(SceneSet::load(scene_path)),
      space_(space),
      options_(std::move(options)) {
  if (options_.work_dir.empty()) throw Error("DEM in the loop needs a folder for its runs");
  if (options_.seeds < 1) throw Error("DEM in the loop: seeds must be at least 1");
  if (options_.jobs < 1) throw Error("DEM in the loop: jobs must be at least 1");
  if (this->outputs().empty()) throw Error("DEM in the loop: no output to predict");
  scene_.check_space(space_, options_.space_path);
  // Every output must be one the tests give, or a ratio of two: found out now, not after the first batch.
  std::set<std::string> known;
  for (const dem::OutputSpec& o : scene_.outputs()) known.insert(o.name);
  for (const std::string& name : this->outputs()) {
    const std::optional<OutputRatio> ratio = parse_output_ratio(name, scene_path + ": output");
    for (const std::string& part : ratio ? std::vector<std::string>{ratio->numerator, ratio->denominator}
                                         : std::vector<std::string>{name})
      if (!known.count(part)) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        throw Error(scene_path + ": the DEM gives no output \"" + part + "\"" +
                    (ratio ? " (in the ratio " + name + ")" : "") + " (it gives " + list + ")");
      }
  }
  make_folder(options_.work_dir);
  make_folder(options_.work_dir + "/points");
}

void DemModel::predict(const double* x, double* y) const {
  std::vector<std::vector<double>> ys;
  predict_batch({std::vector<double>(x, x + inputs().size())}, ys);
  for (std::size_t o = 0; o < ys[0].size(); ++o) y[o] = ys[0][o];
}

void DemModel::predict_batch(const std::vector<std::vector<double>>& xs, std::vector<std::vector<double>>& ys) const {
  // New distinct points get the next run numbers, in the order asked for.
  std::vector<PointSpec> specs;
  std::vector<const std::vector<double>*> new_points;
  for (const std::vector<double>& x : xs) {
    if (x.size() != inputs().size())
      throw Error("DEM model expects " + std::to_string(inputs().size()) + " inputs, got " + std::to_string(x.size()));
    if (evaluated_.count(x)) continue;
    Evaluation& e = evaluated_[x];
    e.run = next_run_++;
    e.x = x;
    order_.push_back(&e);
    new_points.push_back(&e.x);
    const std::map<std::string, double> design = space_.complete(x);
    for (int s = 1; s <= options_.seeds; ++s) {
      PointSpec p;
      p.run = static_cast<int>(e.run);
      p.seed = static_cast<std::uint64_t>(s);
      p.design = design;
      p.scene_fingerprint = scene_.fingerprint();
      p.file = options_.work_dir + "/points/run" + std::to_string(e.run) + "_seed" + std::to_string(s) + ".json";
      specs.push_back(p);
    }
  }
  if (!specs.empty()) {
    const auto start = std::chrono::steady_clock::now();
    PointRunOptions run_options;
    run_options.jobs = options_.jobs;
    run_options.cache_dir = options_.cache_dir;
    run_options.progress = false;
    std::size_t skipped = 0;
    std::vector<json> results = run_points(scene_, specs, run_options, {}, &skipped);
    dem_wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    runs_reused_ += static_cast<long>(skipped);
    runs_made_ += static_cast<long>(specs.size() - skipped);

    // Mean over the seeds of each new point; any failed seed fails the point.
    for (std::size_t k = 0; k < new_points.size(); ++k) {
      Evaluation& e = evaluated_.at(*new_points[k]);
      e.y.assign(outputs().size(), 0.0);
      for (int s = 0; s < options_.seeds; ++s) {
        const json& r = results[k * static_cast<std::size_t>(options_.seeds) + static_cast<std::size_t>(s)];
        if (r.at("status") != "ok") {
          ++e.failed_seeds;
          ++runs_failed_;
          e.reason = r.value("reason", std::string("failed"));
          continue;
        }
        std::map<std::string, double> macro;
        for (auto it = r.at("macro").begin(); it != r.at("macro").end(); ++it)
          if (it.value().is_number()) macro[it.key()] = it.value().get<double>();
        for (std::size_t o = 0; o < outputs().size(); ++o) {
          double value = 0;
          if (!output_value(macro, outputs()[o], value)) {  // an output, or a ratio A/B of two per specimen
            std::string known;
            for (const auto& [name, v] : macro) known += (known.empty() ? "" : ", ") + name;
            throw Error(scene_path_ + ": the DEM gives no output \"" + outputs()[o] + "\" (it gives " + known + ")");
          }
          e.y[o] += value / options_.seeds;
        }
      }
      if (e.failed_seeds > 0) e.y.assign(outputs().size(), std::nan(""));
    }
    write_evaluations();
    if (options_.progress && (dem_wall_s_ - last_report_s_ >= 10.0 || last_report_s_ == 0.0)) {
      last_report_s_ = dem_wall_s_;
      log::info("DEM in the loop: " + std::to_string(points()) + " points, " + std::to_string(runs_made_) +
                " runs made, " + std::to_string(runs_reused_) + " reused, " + std::to_string(runs_failed_) +
                " failed, " + format_duration(dem_wall_s_));
    }
  }
  ys.resize(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) ys[i] = evaluated_.at(xs[i]).y;
}

void DemModel::write_evaluations() const {
  std::ostringstream csv;
  csv << "run";
  for (const std::string& name : inputs()) csv << ',' << name;
  for (const std::string& name : outputs()) csv << ',' << name;
  csv << ",seeds,status\n";
  for (const Evaluation* e : order_) {
    csv << e->run;
    for (double v : e->x) csv << ',' << format_double(v);
    for (double v : e->y) csv << ',' << format_double(v);
    std::string status = e->failed_seeds == 0 ? "ok" : "failed: " + e->reason;
    for (char& c : status)
      if (c == ',' || c == '\n' || c == '"') c = ';';
    csv << ',' << options_.seeds << ',' << status << '\n';
  }
  write_file_atomically(evaluations_csv(), csv.str());
}

}  // namespace demcal::jobs
