// demcal-verify: runs the DEM at a calibrated solution with several seeds and
// writes the verification table (target, mean, SD, CV, 95 % interval, relative
// error, pass, verdict). Seeds are added, up to --max-seeds, until every
// output's interval is narrow enough to judge against the tolerance.
#include <CLI/CLI.hpp>

#include <set>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/cli_main.hpp"
#include "demcal/core/executable_dir.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/jobs/batch.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/core/output_ratio.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/scene_set.hpp"
#include "demcal/inverse/verification.hpp"

namespace {

using namespace demcal;
using nlohmann::json;

struct Arguments {
  std::string solution, scene, space, out, csv, md, work, cache = default_cache_dir();
  std::vector<std::string> sets;
  int seeds = 5, max_seeds = 20, first_seed = 1, jobs = 2, finer_seeds = 5;
  double tolerance = 0.05;
  double scale_resolution = 0.0;  // > 1: also verify with the specimen's radii divided by this
  bool quiet = false;
};

std::string one_decimal(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", x);
  return buffer;
}

std::map<std::string, double> numbers(const json& object, const std::string& where) {
  std::map<std::string, double> out;
  if (!object.is_object()) throw Error(where + " must be an object of name: number");
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (!it.value().is_number()) throw Error(where + "." + it.key() + " must be a number");
    out[it.key()] = it.value().get<double>();
  }
  return out;
}

// The results of run 1 on seeds first..first+n-1 of a finished batch.
std::vector<inverse::SeedRun> stored_seeds(const std::string& out_path, int first, int n) {
  std::vector<inverse::SeedRun> seeds;
  for (int s = first; s < first + n; ++s) {
    const json r = read_json_file(out_path + ".points/run1_seed" + std::to_string(s) + ".json", "DEM result");
    inverse::SeedRun run;
    run.seed = static_cast<std::uint64_t>(s);
    run.ok = r.value("status", std::string()) == "ok";
    run.reason = r.value("reason", std::string());
    if (r.contains("macro"))
      for (auto it = r.at("macro").begin(); it != r.at("macro").end(); ++it)
        if (it.value().is_number()) run.macro[it.key()] = it.value().get<double>();
    seeds.push_back(run);
  }
  return seeds;
}

// Each seed's value of every ratio target A/B (its own A over its own B).
std::vector<inverse::SeedRun> with_ratios(std::vector<inverse::SeedRun> seeds, const std::map<std::string, double>& targets) {
  for (inverse::SeedRun& run : seeds)
    for (const auto& [name, target] : targets) {
      double value = 0;
      if (!run.macro.count(name) && output_value(run.macro, name, value)) run.macro[name] = value;
    }
  return seeds;
}

std::string shift_markdown(const inverse::Verification& coarse, const inverse::Verification& finer, double factor,
                           const json& shifts) {
  std::string md = "\nAt a finer resolution (disk radii / " + format_double(factor) + ", " +
                   std::to_string(finer.seeds.size()) + " seeds):\n\n| output | target | mean | finer mean | "
                   "its 95 % interval | shift % | relative error % | within |\n|---|---|---|---|---|---|---|---|\n";
  char buffer[512];
  for (std::size_t i = 0; i < coarse.rows.size() && i < finer.rows.size(); ++i) {
    const inverse::VerificationRow& c = coarse.rows[i];
    const inverse::VerificationRow& f = finer.rows[i];
    const json& shift = shifts.at(c.output);
    std::snprintf(buffer, sizeof buffer, "| %s | %.4g | %.4g | %.4g | %.4g to %.4g | %+.2f | %+.2f | %s |\n",
                  c.output.c_str(), c.target, c.mean, f.mean, f.ci95_low, f.ci95_high,
                  shift.is_number() ? shift.get<double>() : std::nan(""), f.relative_error_pct, f.passed ? "yes" : "no");
    md += buffer;
  }
  return md;
}

int run(const Arguments& a) {
  if (a.seeds < 1) throw Error("--seeds must be at least 1");
  if (a.scale_resolution != 0.0 && !(a.scale_resolution > 1.0))
    throw Error("--scale-resolution must be above 1 (the factor the disk radii are divided by)");
  if (a.finer_seeds < 2) throw Error("--finer-seeds must be at least 2 (a spread needs two runs)");
  if (a.max_seeds < a.seeds)
    throw Error("--max-seeds (" + std::to_string(a.max_seeds) + ") must be at least --seeds (" + std::to_string(a.seeds) + ")");
  if (a.first_seed < 1) throw Error("--first-seed must be at least 1");
  if (!(a.tolerance > 0)) throw Error("--tolerance must be positive");
  const json solution = read_json_file(a.solution, "solution");
  if (!solution.is_object() || !solution.contains("x") || !solution.contains("targets"))
    throw Error(a.solution + ": not a demcal-invert solution (needs \"x\" and \"targets\")");
  if (solution.contains("status") && !solution.at("status").is_string())
    throw Error(a.solution + ": \"status\" must be a string");
  if (solution.contains("predicted") && !solution.at("predicted").is_object())
    throw Error(a.solution + ": \"predicted\" must be an object of output: number");
  // A minimisation's "targets" are the references its outputs were divided by, not values to meet: what the
  // verification judges then is the optimiser's claim, the outputs it saw at its answer (its "predicted"), against
  // fresh specimens; the references are reported beside (how many times lower the output now is).
  const bool minimise = solution.value("objective_kind", std::string()) == "minimise";
  const std::map<std::string, double> references = numbers(solution.at("targets"), a.solution + ": targets");
  if (references.empty()) throw Error(a.solution + ": targets is empty");
  std::map<std::string, double> targets = references;
  if (minimise)
    for (auto& [name, value] : targets) {
      const json* p = solution.contains("predicted") && solution.at("predicted").contains(name)
                          ? &solution.at("predicted").at(name) : nullptr;
      if (!p || !p->is_number())
        throw Error(a.solution + ": predicted." + name + " is missing: a minimisation is verified against the value "
                    "its optimiser saw at the answer");
      value = p->get<double>();
    }
  if (solution.value("status", std::string("ok")) != "ok")
    log::warn(a.solution + ": the inversion reported status " + solution.value("status", std::string()) +
              "; verifying its nearest point anyway");
  const dem::SceneSet scene = dem::SceneSet::load(a.scene);
  // Check the targets before any DEM run: each must be an output of the scene's test (or tests).
  std::set<std::string> outputs;
  for (const dem::OutputSpec& o : scene.outputs()) outputs.insert(o.name);
  for (const auto& [name, value] : targets) {
    const std::optional<OutputRatio> ratio = parse_output_ratio(name, a.solution + ": targets");
    for (const std::string& part : ratio ? std::vector<std::string>{ratio->numerator, ratio->denominator}
                                         : std::vector<std::string>{name})
      if (!outputs.count(part)) {
        std::string list;
        for (const std::string& o : outputs) list += (list.empty() ? "" : ", ") + o;
        throw Error(a.solution + ": target " + name + ": " + part + " is not an output of " + a.scene +
                    " (its outputs: " + list + ")");
      }
  }

  // The point to run: the solution's parameters, then the space's fixed and
  // tied values, then --set; every name must be a scene parameter.
  std::map<std::string, double> point = numbers(solution.at("x"), a.solution + ": x");
  if (point.empty()) throw Error(a.solution + ": x is empty (no parameter to run)");
  if (!a.space.empty()) {
    ParameterSpace space = ParameterSpace::load(a.space);
    scene.check_space(space, a.space);
    for (const auto& [name, value] : space.fixed())
      if (!point.count(name)) point[name] = value;
    for (const TiedParameter& t : space.tied()) {
      auto source = point.find(t.source);
      if (source != point.end() && !point.count(t.name)) point[t.name] = t.factor * source->second + t.offset;
    }
  }
  for (const std::string& s : a.sets) {
    auto [name, value] = parse_name_value(s, "--set");
    point[name] = value;
  }
  try {
    scene.resolve(point);  // unknown names and values outside the scene's ranges are errors here
  } catch (const Error& e) {
    throw Error(a.solution + ": x: " + e.what());
  }

  const std::string work = a.work.empty() ? a.out + ".runs" : a.work;
  ::mkdir(work.c_str(), 0755);
  Table design(std::vector<int>{1});
  for (const auto& [name, value] : point) design.add_column(name, {value});
  const std::string design_path = work + "/design.csv";
  design.write_csv(design_path);
  jobs::BatchOptions batch;
  batch.scene_path = a.scene;
  batch.design_path = design_path;
  batch.out_path = work + "/runs.h5";
  batch.csv_path = work + "/runs.csv";
  batch.cache_dir = a.cache;
  batch.first_seed = a.first_seed;
  batch.jobs = a.jobs;
  batch.progress = !a.quiet;
  std::map<std::string, double> predicted;
  if (solution.contains("predicted"))
    for (auto it = solution.at("predicted").begin(); it != solution.at("predicted").end(); ++it)
      if (it.value().is_number()) predicted[it.key()] = it.value().get<double>();
  // The surrogate's 95 % prediction interval, shown beside the DEM's interval of the mean.
  inverse::Intervals intervals;
  if (solution.contains("prediction_interval_95") && solution.at("prediction_interval_95").is_object())
    for (auto it = solution.at("prediction_interval_95").begin(); it != solution.at("prediction_interval_95").end(); ++it) {
      const json& pair = it.value();
      if (!pair.is_array() || pair.size() != 2) throw Error(a.solution + ": prediction_interval_95." + it.key() + " must be [low, high]");
      if (pair[0].is_null() || pair[1].is_null()) continue;  // demcal-invert writes null for a non-finite bound
      if (!pair[0].is_number() || !pair[1].is_number())
        throw Error(a.solution + ": prediction_interval_95." + it.key() + " must be [low, high] (numbers)");
      intervals[it.key()] = {pair[0].get<double>(), pair[1].get<double>()};
    }

  // Run n seeds (the batch resumes, so only the new ones run) and judge them.
  double wall_s = 0.0;
  auto judge = [&](int n) {
    batch.seeds = n;
    wall_s += jobs::run_batch(batch).wall_s;
    return inverse::verify(targets, predicted, with_ratios(stored_seeds(batch.out_path, a.first_seed, n), targets),
                           a.tolerance, intervals);
  };
  inverse::Verification v = judge(a.seeds);
  for (;;) {
    const int have = static_cast<int>(v.seeds.size());
    const int want = inverse::seeds_wanted(v, a.max_seeds);
    if (want <= have) {
      v.seeds_stop_reason = inverse::interval_outside_band(v) ? "an interval lies outside the band"
                            : have >= a.max_seeds          ? "--max-seeds reached"
                                                            : "every half-width within the tolerance";
      break;
    }
    if (!a.quiet) {
      std::string widths;
      for (const inverse::VerificationRow& r : v.rows)
        widths += (widths.empty() ? "" : ", ") + r.output + " " + one_decimal(r.half_width_pct) + " %";
      log::info("verification: " + std::to_string(have) + " seeds give 95 % half-widths " + widths + "; running " +
                std::to_string(want - have) + " more (tolerance " + one_decimal(100 * a.tolerance) + " %)");
    }
    v = judge(want);
  }

  json out = inverse::verification_json(v);
  std::string finer_table;
  if (a.scale_resolution > 1.0) {
    // The same point on finer specimens: how far the calibration moves at the resolution a user will run.
    const std::string finer_scene =
        dem::SceneSet::write_with_finer_disks(a.scene, a.scale_resolution, work + "/finer_scene.json");
    jobs::BatchOptions fine = batch;
    fine.scene_path = finer_scene;
    fine.out_path = work + "/finer_runs.h5";
    fine.csv_path = work + "/finer_runs.csv";
    fine.seeds = a.finer_seeds;
    if (!a.quiet)
      log::info("verification at a finer resolution: disk radii / " + format_double(a.scale_resolution) + ", " +
                std::to_string(a.finer_seeds) + " seeds");
    wall_s += jobs::run_batch(fine).wall_s;
    inverse::Verification finer =
        inverse::verify(targets, predicted, with_ratios(stored_seeds(fine.out_path, a.first_seed, a.finer_seeds), targets),
                        a.tolerance);
    json shifts = json::object();
    for (std::size_t i = 0; i < v.rows.size() && i < finer.rows.size(); ++i) {
      const double shift = 100.0 * (finer.rows[i].mean - v.rows[i].mean) / std::fabs(v.rows[i].mean);
      shifts[v.rows[i].output] = std::isfinite(shift) ? json(shift) : json(nullptr);
    }
    json f = inverse::verification_json(finer);
    f["factor"] = a.scale_resolution;
    f["scene"] = finer_scene;
    f["shift_pct"] = shifts;
    out["finer"] = f;
    finer_table = shift_markdown(v, finer, a.scale_resolution, shifts);
  }
  std::string reference_lines;
  if (minimise) {
    out["objective_kind"] = "minimise";
    json ratios = json::object();
    reference_lines = "\nMinimised: the targets above are the values the optimiser saw at its answer; against the "
                      "references it minimised over:\n\n| output | reference | verified mean | mean / reference | "
                      "reference / mean |\n|---|---|---|---|---|\n";
    for (const inverse::VerificationRow& r : v.rows) {
      const double reference = references.at(r.output);
      ratios[r.output] = r.runs > 0 ? json(r.mean / reference) : json(nullptr);
      char buffer[256];
      std::snprintf(buffer, sizeof buffer, "| %s | %.4g | %.4g | %.4f | %.2f |\n", r.output.c_str(), reference, r.mean,
                    r.mean / reference, reference / r.mean);
      reference_lines += buffer;
    }
    out["references"] = references;
    out["mean_over_reference"] = ratios;
  }
  out["parameters"] = point;
  out["scene"] = a.scene;
  out["solution"] = a.solution;
  out["runs"] = batch.out_path;
  out["wall_s"] = wall_s;
  out["max_seeds"] = a.max_seeds;
  write_file_atomically(a.out, out.dump(2) + "\n");
  if (!a.csv.empty()) write_file_atomically(a.csv, inverse::verification_csv(v));
  const std::string table = inverse::verification_markdown(v) + reference_lines + finer_table;
  if (!a.md.empty()) write_file_atomically(a.md, table);
  if (!a.quiet) std::cout << table;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  log::set_program("demcal-verify");
  Arguments a;
  CLI::App app{"demcal-verify: the DEM at a calibrated solution over several seeds, against the targets.\n"
               "  demcal-verify --solution SOLUTION.json --scene S.json [--space S.json] [--seeds 5] [--max-seeds 20] [--tolerance 0.05]\n"
               "                --out VERIFY.json [--csv V.csv] [--md V.md]",
               "demcal-verify"};
  app.add_option("--solution", a.solution, "SOLUTION.json of demcal-invert (x, targets, predicted)")->required();
  app.add_option("--scene", a.scene, "the DEM scene the solution's parameters belong to")->required();
  app.add_option("--space", a.space, "parameter space whose fixed and tied values complete the point");
  app.add_option("--set", a.sets, "NAME=VALUE for another scene parameter (repeatable)");
  app.add_option("--seeds", a.seeds, "DEM seeds S..S+K-1 to start with (S: --first-seed)")->capture_default_str();
  app.add_option("--max-seeds", a.max_seeds,
                 "add seeds up to this many until every output's 95 % half-width is within the tolerance")
      ->capture_default_str();
  app.add_option("--first-seed", a.first_seed,
                 "first DEM seed (after a calibration on specimens 1..n, verify on others: n + 1)")
      ->capture_default_str();
  app.add_option("--jobs", a.jobs, "seeds run at once")->capture_default_str();
  app.add_option("--tolerance", a.tolerance, "largest relative error that passes")->capture_default_str();
  app.add_option("--scale-resolution", a.scale_resolution,
                 "also verify with the specimen's disk radii divided by this factor (> 1) and report the shift");
  app.add_option("--finer-seeds", a.finer_seeds, "seeds of the finer verification")->capture_default_str();
  app.add_option("--out", a.out, "verification JSON")->required();
  app.add_option("--csv", a.csv, "verification table as CSV");
  app.add_option("--md", a.md, "verification table as Markdown");
  app.add_option("--work", a.work, "folder of the DEM runs (default OUT.runs; rerunning resumes)");
  app.add_option("--cache", a.cache, "packed specimens")->capture_default_str();
  app.add_flag("--quiet", a.quiet, "no table or progress on stdout/stderr");
  return cli::run_main(app, argc, argv, [&]() {
    if (a.quiet) log::set_level(log::Level::Quiet);
    return run(a);
  });
}
