// demcal-fit: fits a response surface (linear or quadratic) or a GA-BP
// network to data and saves it as a model file.
#include <CLI/CLI.hpp>

#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/output_ratio.hpp"
#include "demcal/core/cli_main.hpp"
#include "demcal/core/atomic_file.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/surrogate/data_columns.hpp"
#include "demcal/surrogate/gabp.hpp"
#include "demcal/surrogate/model_file.hpp"
#include "demcal/surrogate/neural_network_model.hpp"
#include "demcal/surrogate/reports.hpp"
#include "demcal/surrogate/response_surface_model.hpp"

namespace {

using namespace demcal;
using namespace demcal::surrogate;

struct Arguments {
  std::string kind, data, x, out, space, report, residuals, hidden = "auto";
  std::vector<std::string> y;
  std::uint64_t seed = 1;
  double validation_fraction = 0.25;
  double eliminate = 0.0;
  int ga_population = 40, ga_generations = 40;
  bool quiet = false;
};

const std::vector<std::string> kSurfaceOptions = {"--space", "--eliminate"};
const std::vector<std::string> kGabpOptions = {"--hidden", "--validation-fraction", "--ga-population",
                                               "--ga-generations"};

std::vector<FactorCoding> coding_from_space(const std::string& path, const std::vector<std::string>& factors) {
  ParameterSpace space = ParameterSpace::load(path);
  std::vector<FactorCoding> coding;
  for (const std::string& f : factors) {
    const Parameter& p = space.parameters()[space.index_of(f)];
    coding.push_back({0.5 * (p.low + p.high), 0.5 * (p.high - p.low)});
  }
  return coding;
}

std::string surface_residuals_csv(const std::vector<SurfaceFit>& fits, const Table& table) {
  std::ostringstream csv;
  csv << "run,response,observed,fitted,residual,press_residual\n";
  for (const SurfaceFit& f : fits)
    for (Eigen::Index i = 0; i < f.observed.size(); ++i)
      csv << table.run_ids()[static_cast<std::size_t>(i)] << ',' << f.response << ',' << format_double(f.observed(i))
          << ',' << format_double(f.fitted(i)) << ',' << format_double(f.observed(i) - f.fitted(i)) << ','
          << format_double(f.press_residuals(i)) << '\n';
  return csv.str();
}

std::string gabp_residuals_csv(const GabpFit& fit, const Model& model, const Eigen::MatrixXd& X,
                               const Eigen::MatrixXd& Y, const Table& table) {
  std::ostringstream csv;
  csv << "run,set,response,observed,fitted,residual\n";
  std::vector<std::string> set(static_cast<std::size_t>(X.rows()), "training");
  for (int r : fit.validation_rows) set[static_cast<std::size_t>(r)] = "validation";
  std::vector<double> x(static_cast<std::size_t>(X.cols())), y(static_cast<std::size_t>(Y.cols()));
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (Eigen::Index j = 0; j < X.cols(); ++j) x[static_cast<std::size_t>(j)] = X(i, j);
    model.predict(x.data(), y.data());
    for (Eigen::Index o = 0; o < Y.cols(); ++o)
      csv << table.run_ids()[static_cast<std::size_t>(i)] << ',' << set[static_cast<std::size_t>(i)] << ','
          << fit.outputs[static_cast<std::size_t>(o)] << ',' << format_double(Y(i, o)) << ','
          << format_double(y[static_cast<std::size_t>(o)]) << ',' << format_double(Y(i, o) - y[static_cast<std::size_t>(o)])
          << '\n';
  }
  return csv.str();
}

int run(const Arguments& a, const CLI::App& app) {
  const bool surface = a.kind == "quadratic" || a.kind == "linear";
  for (const std::string& option : surface ? kGabpOptions : kSurfaceOptions)
    if (app.count(option) > 0) throw Error("option " + option + " does not apply to " + a.kind);
  if (surface && app.count("--seed") > 0)
    log::detail("--seed: a least-squares surface has nothing random; the seed does not change it");
  Table table = cli::read_data(a.data);
  std::vector<std::string> x_names = split_names(a.x, "--x");
  std::vector<std::string> y_names;
  for (const std::string& y : a.y)
    for (const std::string& name : split_names(y, "--y")) {
      if (std::find(y_names.begin(), y_names.end(), name) != y_names.end()) throw Error("--y: \"" + name + "\" is listed twice");
      y_names.push_back(name);
    }
  if (x_names.empty()) throw Error("--x A,B,... is required (the input columns)");
  if (y_names.empty()) throw Error("--y R is required (the response column; repeat for several)");
  for (const std::string& y : y_names)
    if (std::find(x_names.begin(), x_names.end(), y) != x_names.end()) throw Error("column " + y + " is both an input (--x) and a response (--y)");
  add_ratio_columns(table, y_names, a.data);  // a response A/B: each run's A over its B
  Eigen::MatrixXd X = select_columns(table, x_names, a.data);
  Eigen::MatrixXd Y = select_columns(table, y_names, a.data);
  require_varying(X, x_names, a.data, "an input must vary to be fitted");
  require_varying(Y, y_names, a.data, "there is nothing to fit");

  std::string report;
  nlohmann::json file;
  if (surface) {
    SurfaceOptions options;
    options.kind = a.kind == "linear" ? SurfaceKind::Linear : SurfaceKind::Quadratic;
    if (!a.space.empty()) options.coding = coding_from_space(a.space, x_names);
    if (a.eliminate < 0 || a.eliminate >= 1) throw Error("--eliminate ALPHA must be in (0, 1), e.g. 0.05");
    options.eliminate_alpha = a.eliminate;
    std::vector<SurfaceFit> fits;
    for (Eigen::Index o = 0; o < Y.cols(); ++o) {
      try {
        fits.push_back(fit_surface(x_names, X, Y.col(o), y_names[static_cast<std::size_t>(o)], options));
      } catch (const Error& e) {
        throw Error(a.data + ": " + e.what());  // what the data lacks (runs, variation, estimable terms)
      }
      report += surface_markdown(fits.back());
    }
    file = surface_model_json(fits, a.data);
    if (!a.residuals.empty()) write_file_atomically(a.residuals, surface_residuals_csv(fits, table));
  } else {
    GabpOptions options;
    if (a.hidden != "auto") {
      double h = 0;
      if (!parse_double(a.hidden, h) || h < 1 || h != static_cast<int>(h))
        throw Error("--hidden \"" + a.hidden + "\" (expected auto or a positive integer)");
      options.hidden = static_cast<int>(h);
    }
    options.validation_fraction = a.validation_fraction;
    options.seed = a.seed;
    options.ga_population = a.ga_population;
    options.ga_generations = a.ga_generations;
    options.progress = !a.quiet;
    GabpFit fit = [&] {
      try {
        return fit_gabp(x_names, X, y_names, Y, options);
      } catch (const Error& e) {
        throw Error(a.data + ": " + e.what());
      }
    }();
    report = gabp_markdown(fit);
    file = gabp_model_json(fit, a.data);
    if (!a.residuals.empty())
      write_file_atomically(a.residuals, gabp_residuals_csv(fit, *model_from_json(file, a.out), X, Y, table));
  }
  save_model(file, a.out);
  if (!a.report.empty()) write_file_atomically(a.report, report);
  if (!a.quiet) std::cout << report;
  log::info("wrote " + a.kind + " model of " + std::to_string(y_names.size()) + " output(s) to " + a.out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  log::set_program("demcal-fit");
  Arguments a;
  CLI::App app{
      "demcal-fit: fits a surrogate model to data and saves it (JSON).\n"
      "  demcal-fit quadratic|linear|gabp --data FILE.csv --x A,B,... --y R [--y R2 ...] --out MODEL.json\n"
      "             [--seed S] [--hidden auto|N] [--validation-fraction F] [--space S.json] [--eliminate ALPHA]",
      "demcal-fit"};
  app.add_option("kind", a.kind, "quadratic, linear or gabp")->required()->check(CLI::IsMember({"quadratic", "linear", "gabp"}));
  app.add_option("--data", a.data, "data .csv or .h5 (inputs and responses as columns)")->required();
  app.add_option("--x", a.x, "input columns, comma separated, in this order")->required();
  app.add_option("--y", a.y, "response column(s); repeat or comma separate")->required();
  app.add_option("--out", a.out, "model JSON")->required();
  app.add_option("--report", a.report, "also write the fit report (Markdown) here");
  app.add_option("--residuals", a.residuals, "CSV of observed, fitted and residuals per run (for plots)");
  app.add_option("--space", a.space, "quadratic/linear: code -1/+1 at the space's low/high (a CCD's cube) instead of the data's min/max");
  app.add_option("--eliminate", a.eliminate, "quadratic/linear: backward elimination at this alpha, keeping hierarchy");
  app.add_option("--hidden", a.hidden, "gabp: hidden neurons, or auto (round(sqrt(m+n)) + 1..10 by validation R^2)")
      ->capture_default_str();
  app.add_option("--validation-fraction", a.validation_fraction, "gabp: share of rows held out for early stopping")
      ->capture_default_str();
  app.add_option("--ga-population", a.ga_population, "gabp: GA population for the initial weights")->capture_default_str();
  app.add_option("--ga-generations", a.ga_generations, "gabp: GA generations")->capture_default_str();
  app.add_option("--seed", a.seed, "gabp: seed of the split, the GA and the training (surfaces: accepted, no effect)")
      ->capture_default_str();
  app.add_flag("--quiet", a.quiet, "no report on stdout, no progress on stderr");
  return cli::run_main(app, argc, argv, [&]() {
    if (a.quiet) log::set_level(log::Level::Quiet);
    return run(a, app);
  });
}
