// demcal-invert: finds micro-parameters whose predicted macro values match
// targets, on saved models (response surfaces, GA-BP networks) or on the DEM
// itself (DEM in the loop, --dem-scene).
#include <CLI/CLI.hpp>

#include <iostream>

#include <nlohmann/json.hpp>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/cli_main.hpp"
#include "demcal/core/executable_dir.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/jobs/dem_model.hpp"
#include "demcal/inverse/inversion.hpp"
#include "demcal/surrogate/model_file.hpp"

namespace {

using namespace demcal;
using namespace demcal::inverse;

// Exit codes: a target no point in the domain can reach; targets attainable
// one by one that the best point found still misses.
constexpr int kUnreachable = 3;
constexpr int kNotMet = 4;

struct Arguments {
  std::vector<std::string> models, targets, sets;
  std::string space, algorithm = "ga", objective = "sum-rel", out, history;
  std::string dem_scene, dem_work, cache = default_cache_dir();
  int dem_seeds = 1, jobs = 1;
  bool polish = false, quiet = false;
  int restarts = 1, samples = 5000, attainable_samples = 2000;
  std::uint64_t seed = 1;
  long budget = 100000;
  double stop_below = -1.0, tolerance = 0.05, reach_tolerance = 0.01;
};

int run(const Arguments& a, const CLI::App& app) {
  if (a.algorithm != "search" && (app.count("--samples") || app.count("--tolerance")))
    throw Error("--samples and --tolerance apply to --algo search");
  const bool dem_in_loop = !a.dem_scene.empty();
  if (dem_in_loop == !a.models.empty()) throw Error("give --model (a saved surrogate) or --dem-scene (DEM in the loop), not both");
  if (!dem_in_loop)
    for (const char* option : {"--dem-seeds", "--dem-work", "--jobs", "--cache"})
      if (app.count(option)) throw Error(std::string(option) + " applies to --dem-scene only");
  if (dem_in_loop && a.polish) throw Error("--polish needs a smooth surrogate (finite differences of a DEM run are noise)");
  if (dem_in_loop && app.count("--attainable-samples"))
    throw Error("--attainable-samples does not apply to --dem-scene (each sample would be a DEM run)");
  std::vector<Target> targets;
  for (const std::string& t : a.targets) {
    auto [name, value] = parse_name_value(t, "--target");
    targets.push_back({name, value});
  }
  std::unique_ptr<ParameterSpace> space;
  if (!a.space.empty()) space = std::make_unique<ParameterSpace>(ParameterSpace::load(a.space));
  if (dem_in_loop && !space) throw Error("--dem-scene needs --space: the parameters to calibrate, their bounds and fixed values");

  std::vector<std::unique_ptr<Model>> owned;
  std::vector<const Model*> models;
  jobs::DemModel* dem_model = nullptr;
  for (const std::string& path : a.models) {
    owned.push_back(surrogate::load_model(path));
    models.push_back(owned.back().get());
  }
  if (dem_in_loop) {
    jobs::DemModelOptions options;
    options.work_dir = a.dem_work.empty() ? a.out + ".dem" : a.dem_work;
    options.seeds = a.dem_seeds;
    options.jobs = a.jobs;
    options.cache_dir = a.cache;
    options.progress = !a.quiet;
    options.space_path = a.space;
    std::vector<std::string> outputs;
    for (const Target& t : targets) outputs.push_back(t.output);
    owned.push_back(std::make_unique<jobs::DemModel>(a.dem_scene, *space, outputs, options));
    dem_model = static_cast<jobs::DemModel*>(owned.back().get());
    models.push_back(dem_model);
  }
  InversionProblem problem(models, space.get(), targets, parse_objective(a.objective));
  for (const std::string& w : problem.warnings()) log::warn(w);

  InversionSettings settings;
  settings.algorithm = a.algorithm;
  for (const std::string& s : a.sets) settings.optimizer_settings.insert(parse_name_value(s, "--set"));
  settings.restarts = a.restarts;
  settings.seed = a.seed;
  settings.polish = a.polish;
  if (a.budget < 1) throw Error("--budget must be at least 1 evaluation");
  settings.budget.max_evaluations = a.budget;
  // Wang & Cao stop the annealing below 10 % error; the others run to convergence.
  // A minimisation has no error to stop below: it runs its budget unless told otherwise.
  const bool annealing = a.algorithm == "sa" || a.algorithm == "sa-vfsr";
  double stop = a.stop_below >= 0 ? a.stop_below : (annealing && a.objective != "minimise" ? 0.10 : -1.0);
  if (stop >= 0) settings.budget.target_value = stop;
  settings.search.samples = a.samples;
  settings.search.tolerance = a.tolerance;
  settings.reach_tolerance = a.reach_tolerance;
  settings.attainable_samples = dem_in_loop ? 0 : a.attainable_samples;

  InversionResult result = invert(problem, settings);
  nlohmann::json solution = solution_json(problem, settings, result);
  if (dem_model) {
    // Every DEM run the calibration needed, including those an interrupted
    // earlier attempt made (reused, not repeated).
    solution["dem"] = {{"scene", a.dem_scene},
                       {"seeds_per_point", a.dem_seeds},
                       {"points", dem_model->points()},
                       {"runs", dem_model->points() * a.dem_seeds},
                       {"runs_made_now", dem_model->runs_made()},
                       {"runs_reused", dem_model->runs_reused()},
                       {"runs_failed", dem_model->runs_failed()},
                       {"dem_wall_s", dem_model->dem_wall_s()},
                       {"jobs", a.jobs},
                       {"evaluations_csv", dem_model->evaluations_csv()}};
  }
  write_file_atomically(a.out, solution.dump(2) + "\n");
  if (!a.history.empty()) write_file_atomically(a.history, history_csv(settings, result));

  std::string x;
  for (std::size_t j = 0; j < problem.parameter_names().size(); ++j)
    x += (x.empty() ? "" : ", ") + problem.parameter_names()[j] + " = " + format_double(result.x[j]);
  log::info(a.algorithm + ": " + result.status + ", " + to_string(problem.objective_kind()) + " " +
            format_double(result.objective) + " (max relative error " + format_double(result.max_relative_error) +
            ") after " + std::to_string(result.evaluations) + " evaluations in " + format_double(result.wall_s) + " s: " + x);
  if (dem_model)
    log::info("DEM in the loop: " + std::to_string(dem_model->points() * a.dem_seeds) + " DEM runs (" +
              std::to_string(dem_model->runs_made()) + " made now, " + std::to_string(dem_model->runs_reused()) +
              " reused from an earlier attempt); runs listed in " + dem_model->evaluations_csv());
  for (const auto& name : solution["unidentified"])
    log::info("not identified by these targets: " + name.get<std::string>());
  if (result.status == "unreachable") {
    log::error("targets unreachable within the domain: " + solution["reason"].get<std::string>() +
               "; nearest attainable written to " + a.out);
    return kUnreachable;
  }
  if (result.status == "not_met") {
    log::error("targets not met: " + solution["reason"].get<std::string>() + "; best point written to " + a.out);
    return kNotMet;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  log::set_program("demcal-invert");
  Arguments a;
  CLI::App app{
      "demcal-invert: micro-parameters whose predicted macro values match targets.\n"
      "  demcal-invert --model M1.json [--model M2.json ...] --target NAME=VALUE [--target ...] [--space S.json]\n"
      "  demcal-invert --dem-scene SCENE.json --space S.json --target NAME=VALUE ... [--dem-seeds K] [--jobs J]\n"
      "                [--algo ga|sa|sa-vfsr|wca|lhs-wca|hs|search] [--objective sum-rel|max-rel|sse-rel|minimise] [--polish]\n"
      "                [--restarts R] [--seed S] --out SOLUTION.json",
      "demcal-invert"};
  app.add_option("--model", a.models, "saved model (demcal-fit); repeat for several");
  app.add_option("--dem-scene", a.dem_scene, "DEM in the loop: every evaluation is a DEM run of this scene (needs --space)");
  app.add_option("--dem-seeds", a.dem_seeds, "DEM in the loop: specimens per point (outputs are their mean)")
      ->capture_default_str();
  app.add_option("--jobs", a.jobs, "DEM in the loop: points run at once")->capture_default_str();
  app.add_option("--dem-work", a.dem_work, "DEM in the loop: folder of its runs (default OUT.dem); a rerun resumes from it");
  app.add_option("--cache", a.cache, "DEM in the loop: folder of cached packed specimens")->capture_default_str();
  app.add_option("--target", a.targets, "NAME=VALUE of a model output; repeat for several");
  bool list_algorithms = false;
  app.add_flag("--list-algorithms", list_algorithms, "print the algorithms and objectives (JSON) and exit");
  app.add_option("--space", a.space, "parameter space JSON: bounds, fixed and tied values (default: the models' domains)");
  app.add_option("--algo", a.algorithm, "ga, sa, sa-vfsr, wca, lhs-wca, hs or search")->capture_default_str();
  app.add_option("--objective", a.objective,
                 "sum-rel, max-rel or sse-rel (relative errors to the targets), or minimise (the outputs over the "
                 "--target values as references, e.g. a fitness to drive down)")->capture_default_str();
  app.add_flag("--polish", a.polish, "polish the best point by bounded least squares (Ceres)");
  app.add_option("--restarts", a.restarts, "independent runs with seeds S, S+1, ...")->capture_default_str();
  app.add_option("--seed", a.seed, "seed of the first run")->capture_default_str();
  app.add_option("--out", a.out, "SOLUTION.json");
  app.add_option("--history", a.history, "convergence record CSV (best objective against evaluations)");
  app.add_option("--set", a.sets, "optimiser setting NAME=VALUE, e.g. population=300 (ga, wca), T0=100 (sa)");
  app.add_option("--budget", a.budget, "evaluations per run")->capture_default_str();
  app.add_option("--stop-below", a.stop_below, "stop a run once the objective is below this (sa default 0.10)");
  app.add_option("--samples", a.samples, "search: Latin-hypercube points per run")->capture_default_str();
  app.add_option("--tolerance", a.tolerance, "search: keep points within this relative error of every target")
      ->capture_default_str();
  app.add_option("--reach-tolerance", a.reach_tolerance, "reached when every target is within this relative error")
      ->capture_default_str();
  app.add_option("--attainable-samples", a.attainable_samples, "points sampled for the attainable output ranges")
      ->capture_default_str();
  app.add_flag("--quiet", a.quiet, "no summary on stderr");
  return cli::run_main(app, argc, argv, [&]() {
    if (a.quiet) log::set_level(log::Level::Quiet);
    if (list_algorithms) {
      std::vector<std::string> algorithms = inverse::optimizer_names();
      algorithms.push_back("search");  // tolerance search + mean shift: not an optimiser
      std::cout << nlohmann::json({{"algorithms", algorithms}, {"objectives", inverse::objective_names()}}).dump(2) << "\n";
      return 0;
    }
    if (a.targets.empty()) throw Error("--target NAME=VALUE is required");
    if (a.out.empty()) throw Error("--out is required");
    return run(a, app);
  }, "3 a target outside what the domain can reach; 4 targets attainable but not met");
}
