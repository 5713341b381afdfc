// demcal-doe: writes a design of experiments (coded and natural units) and
// its property report.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "demcal/core/cli_main.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/dem/scene_set.hpp"
#include "demcal/doe/design_kinds.hpp"
#include "demcal/doe/factorial.hpp"
#include "demcal/doe/natural_units.hpp"
#include "demcal/doe/orthogonal_array.hpp"
#include "demcal/doe/physical_range.hpp"
#include "demcal/doe/properties.hpp"
#include "demcal/doe/response_surface.hpp"
#include "demcal/doe/space_filling.hpp"

namespace {

using namespace demcal;

struct Arguments {
  std::string kind;
  std::string space_path;
  std::string scene_path;
  int factors = 0;
  std::string out;
  std::uint64_t seed = 1;
  bool report = false;
  bool quiet = false;
  int runs = 0;
  std::string levels;
  int blanks = 0;
  std::string doubled = "low";
  std::string generators;
  std::string alpha = "rotatable";
  int center = -1;
  std::string type = "circumscribed";
  std::string criterion = "random";
  int iterations = 0;
};

// Options that belong to some kinds only; giving one to another kind is an
// error, not a silent no-op (design_kinds.hpp says which).
const std::vector<std::string> kKindOptions = {"--runs", "--levels", "--blank", "--doubled-level", "--generators",
                                               "--alpha", "--center", "--type", "--criterion", "--iterations"};

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, ',');)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

// Level count shared by all parameters of the space, or 0.
int common_space_levels(const ParameterSpace& space) {
  int levels = -1;
  for (const Parameter& p : space.parameters()) {
    int n = static_cast<int>(p.levels.size());
    if (levels < 0) levels = n;
    if (n != levels) return 0;
  }
  return levels < 0 ? 0 : levels;
}

doe::Design build(const Arguments& a, int factors, const ParameterSpace* space) {
  auto need_runs = [&]() {
    if (a.runs <= 0) throw Error(a.kind + ": --runs N is required");
    return a.runs;
  };
  if (a.kind == "oa") {
    std::string levels = a.levels;
    if (levels.empty() && space) {
      int common = common_space_levels(*space);
      if (common == 0) throw Error("oa: give --levels (the space's parameters do not all list the same number of levels)");
      levels = std::to_string(common);
    }
    if (levels.empty()) throw Error("oa: --levels is required (e.g. 3, or 2^1,3^7)");
    doe::OaRequest request;
    request.runs = need_runs();
    request.levels = doe::parse_levels(levels, factors);
    request.blanks = a.blanks;
    request.doubled = a.doubled;
    int requested = 0;
    for (auto [level, count] : request.levels) requested += count;
    if (factors > 0 && requested != factors)
      throw Error("oa: --levels " + levels + " names " + std::to_string(requested) + " factors, but there are " +
                  std::to_string(factors));
    doe::Design design = doe::orthogonal_array(request);
    for (std::size_t j = static_cast<std::size_t>(requested); j < design.width(); ++j) design.blank[j] = true;
    return design;
  }
  if (a.kind == "fullfact") {
    if (a.levels.empty()) throw Error("fullfact: --levels is required (one count for all factors, or one per factor)");
    std::vector<int> levels;
    for (const std::string& part : split_list(a.levels)) {
      try {
        levels.push_back(std::stoi(part));
      } catch (const std::exception&) {
        throw Error("fullfact: --levels \"" + a.levels + "\": expected integers");
      }
    }
    if (levels.size() == 1) levels.assign(static_cast<std::size_t>(factors), levels[0]);
    if (static_cast<int>(levels.size()) != factors)
      throw Error("fullfact: --levels lists " + std::to_string(levels.size()) + " counts for " + std::to_string(factors) + " factors");
    return doe::full_factorial(levels);
  }
  if (a.kind == "fracfact") return doe::fractional_factorial(factors, split_list(a.generators), a.runs);
  if (a.kind == "pb") return doe::plackett_burman(factors, a.runs);
  if (a.kind == "ccd") {
    doe::CcdOptions options;
    options.factors = factors;
    options.alpha = a.alpha;
    options.center = a.center;
    options.type = a.type;
    return doe::central_composite(options);
  }
  if (a.kind == "bbd") return doe::box_behnken(factors, a.center);
  if (a.kind == "lhs") {
    doe::LhsOptions options;
    options.runs = need_runs();
    options.factors = factors;
    options.criterion = doe::parse_lhs_criterion(a.criterion);
    options.seed = a.seed;
    options.outer_iterations = a.iterations;
    return doe::latin_hypercube(options);
  }
  if (a.kind == "sobol") return doe::sobol(need_runs(), factors, a.seed);
  throw Error("design kind \"" + a.kind + "\" has no generator");  // design_kinds() lists one without a branch here
}

// Nothing is written when a design point leaves a parameter's physical range:
// every such parameter is named (one line each) with the fix.
void refuse_unphysical(const Table& table, const ParameterSpace& space,
                       const std::map<std::string, doe::PhysicalBounds>& scene_bounds, const Arguments& a) {
  const std::vector<std::string> problems = doe::physical_range_problems(table, space, scene_bounds);
  if (problems.empty()) return;
  std::string message = a.space_path + ": the " + a.kind + " design leaves the physical range of " +
                        std::to_string(problems.size()) + " parameter(s):";
  for (const std::string& p : problems) message += "\n  " + p;
  message += a.kind == "ccd" && a.type == "circumscribed"
                 ? "\n  fix: --type inscribed or --type faced (axial points inside the bounds), or bounds farther from "
                   "the physical limit"
                 : "\n  fix: bounds inside the physical range";
  throw Error(message);
}

int run(const Arguments& a, const CLI::App& app) {
  if (a.kind.empty()) throw Error("give a design kind (demcal-doe --list-kinds lists them)");
  if (a.out.empty()) throw Error("--out is required (FILE.csv or FILE.h5)");
  const doe::DesignKind& kind = doe::find_design_kind(a.kind);
  for (const std::string& name : kKindOptions)
    if (app.count(name) > 0 && std::find(kind.options.begin(), kind.options.end(), name) == kind.options.end())
      throw Error("option " + name + " does not apply to " + a.kind);
  if (a.center < -1) throw Error(a.kind + ": --center must be >= 0");

  std::unique_ptr<ParameterSpace> space;
  int factors = a.factors;
  if (!a.space_path.empty()) {
    space = std::make_unique<ParameterSpace>(ParameterSpace::load(a.space_path));
    if (factors > 0 && factors != static_cast<int>(space->size()))
      throw Error("--factors " + std::to_string(factors) + " disagrees with " + a.space_path + ", which has " +
                  std::to_string(space->size()) + " parameters");
    factors = static_cast<int>(space->size());
  }
  if (factors <= 0 && a.kind == "oa" && a.levels.find('^') != std::string::npos) {
    for (auto [level, count] : doe::parse_levels(a.levels, 0)) factors += count;
  }
  if (factors <= 0) throw Error("give --space FILE.json or --factors N (N >= 1)");
  if (factors < kind.min_factors || (kind.max_factors > 0 && factors > kind.max_factors))
    throw Error(a.kind + ": " + kind.title + " designs need " + std::to_string(kind.min_factors) +
                (kind.max_factors > 0 ? ".." + std::to_string(kind.max_factors) : " or more") + " factors (got " +
                std::to_string(factors) + ")");

  if (!a.scene_path.empty() && !space) throw Error("--scene checks a design in natural units: give --space too");
  std::map<std::string, doe::PhysicalBounds> scene_bounds;
  if (!a.scene_path.empty()) {
    const dem::SceneSet scene = dem::SceneSet::load(a.scene_path);
    scene.check_space(*space, a.space_path);
    for (const auto& [name, p] : scene.parameters()) scene_bounds[name] = {p.low, p.high};
  }

  doe::Design design = build(a, factors, space.get());
  design.settings["seed"] = std::to_string(a.seed);
  if (space) doe::name_factors(design, *space);
  Table table = doe::design_table(design, space.get());
  if (space) refuse_unphysical(table, *space, scene_bounds, a);
  if (space) table.attributes()["space"] = a.space_path;
  table.write(a.out, "/design");
  log::info("wrote " + std::to_string(design.runs()) + " runs of " + design.description + " to " + a.out);
  if (a.report) std::cout << doe::properties_markdown(design, doe::analyse(design));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  demcal::log::set_program("demcal-doe");
  Arguments a;
  CLI::App app{
      "demcal-doe: designs of experiments in coded and natural units.\n"
      "  demcal-doe KIND (--space FILE.json | --factors N) [options] --out FILE.csv|FILE.h5 [--seed S] [--report]\n"
      "KIND: oa, fullfact, fracfact, pb, ccd, bbd, lhs, sobol",
      "demcal-doe"};
  bool list_kinds = false;
  app.add_option("kind", a.kind, "design kind: oa, fullfact, fracfact, pb, ccd, bbd, lhs, sobol");
  app.add_flag("--list-kinds", list_kinds, "print the design kinds, their options and factor limits (JSON) and exit");
  app.add_option("--space", a.space_path, "parameter space JSON: factor names, bounds and levels (natural units)");
  app.add_option("--scene", a.scene_path,
                 "scene JSON: refuse a design that leaves the scene's physical bounds of a parameter (needs --space)");
  app.add_option("--factors", a.factors, "number of factors (columns x1..xN in coded units)");
  app.add_option("--out", a.out, "output design: .csv for people, .h5 for the pipeline");
  app.add_option("--seed", a.seed, "seed for randomised designs (lhs, sobol)")->capture_default_str();
  app.add_flag("--report", a.report, "print the design's property report (Markdown) on stdout");
  app.add_flag("--quiet", a.quiet, "no progress messages on stderr");
  app.add_option("--runs", a.runs, "oa, fracfact, pb, lhs, sobol: number of runs");
  app.add_option("--levels", a.levels, "oa: levels (3, or groups 2^1,3^7); fullfact: one count or one per factor");
  app.add_option("--blank", a.blanks, "oa: extra blank (error) columns after the factors")->capture_default_str();
  app.add_option("--doubled-level", a.doubled, "oa, collapsed arrays: level that takes the collapsed one (low, middle, high)")
      ->capture_default_str();
  app.add_option("--generators", a.generators, "fracfact: generators of the added factors, e.g. D=ABC,E=ABD");
  app.add_option("--alpha", a.alpha, "ccd: rotatable, orthogonal, face or a number")->capture_default_str();
  app.add_option("--center", a.center, "ccd, bbd: centre points (default as Minitab)");
  app.add_option("--type", a.type, "ccd: circumscribed, inscribed or faced")->capture_default_str();
  app.add_option("--criterion", a.criterion, "lhs: random, center, maximin or phip")->capture_default_str();
  app.add_option("--iterations", a.iterations, "lhs maximin/phip: outer iterations of the optimiser (0: by size)");
  return demcal::cli::run_main(app, argc, argv, [&]() {
    if (a.quiet) demcal::log::set_level(demcal::log::Level::Quiet);
    if (list_kinds) {
      std::cout << demcal::doe::design_kinds_json().dump(2) << "\n";
      return 0;
    }
    return run(a, app);
  });
}
