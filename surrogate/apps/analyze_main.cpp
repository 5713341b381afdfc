// demcal-analyze: range analysis and ANOVA of designed experiments, and
// global sensitivity (Sobol, Morris) of saved models.
#include <CLI/CLI.hpp>

#include <iostream>

#include <nlohmann/json.hpp>

#include "demcal/core/cli_main.hpp"
#include "demcal/core/atomic_file.hpp"
#include "demcal/core/output_ratio.hpp"
#include "demcal/surrogate/data_columns.hpp"
#include "demcal/surrogate/design_anova.hpp"
#include "demcal/surrogate/model_file.hpp"
#include "demcal/surrogate/range_analysis.hpp"
#include "demcal/surrogate/reports.hpp"
#include "demcal/surrogate/sensitivity.hpp"

namespace {

using namespace demcal;
using namespace demcal::surrogate;

struct Arguments {
  std::string command;
  std::string data, factors, responses, error = "residual", pool, format = "md", out;
  double pool_below = 0.0;
  std::string model;
  int samples = 4096, trajectories = 50;
  std::uint64_t seed = 1;
};

void emit(const std::string& text, const std::string& out) {
  if (out.empty())
    std::cout << text;
  else
    write_file_atomically(out, text);
}

int design_analysis(const Arguments& a) {
  if (a.format != "md" && a.format != "json" && a.format != "csv")
    throw Error("--format \"" + a.format + "\" (expected md, json or csv)");
  Table table = cli::read_data(a.data);
  std::vector<std::string> factors = split_names(a.factors, "--factors");
  std::vector<std::string> responses = split_names(a.responses, "--responses");
  if (factors.empty()) throw Error("--factors A,B,... is required (the design columns)");
  if (responses.empty()) throw Error("--responses R1,R2,... is required");
  add_ratio_columns(table, responses, a.data);  // a response A/B: each run's A over its B
  for (const std::string& r : responses)
    if (std::find(factors.begin(), factors.end(), r) != factors.end())
      throw Error("column " + r + " is both a factor (--factors) and a response (--responses)");

  DesignAnovaOptions options;
  if (a.error.rfind("column:", 0) == 0) {
    options.error_column = a.error.substr(7);
    if (options.error_column.empty()) throw Error("--error column:NAME needs a column name");
  } else if (a.error != "residual") {
    throw Error("--error \"" + a.error + "\" (expected residual or column:NAME)");
  }
  if (a.command == "range" && (a.error != "residual" || !a.pool.empty() || a.pool_below > 0))
    throw Error("--error and --pool apply to anova, not range");
  options.pool = split_names(a.pool, "--pool");
  options.pool_below_f = a.pool_below;
  if (a.pool_below < 0) throw Error("--pool-below must be >= 0");

  std::vector<std::string> columns = factors;
  if (!options.error_column.empty() && std::find(columns.begin(), columns.end(), options.error_column) == columns.end())
    columns.push_back(options.error_column);
  Eigen::MatrixXd X = select_columns(table, columns, a.data);
  std::vector<RangeAnalysis> ranges;
  std::vector<DesignAnova> anovas;
  for (const std::string& response : responses) {
    Eigen::VectorXd y = select_columns(table, {response}, a.data).col(0);
    try {
      if (a.command == "range")
        ranges.push_back(range_analysis(factors, X.leftCols(static_cast<Eigen::Index>(factors.size())), y, response));
      else
        anovas.push_back(design_anova(columns, X, y, factors, response, options));
    } catch (const Error& e) {
      throw Error(a.data + ": " + e.what());  // what the data lacks (levels, runs)
    }
  }
  std::string text;
  if (a.command == "range")
    text = a.format == "json" ? range_json(ranges).dump(2) + "\n" : a.format == "csv" ? range_csv(ranges) : range_markdown(ranges);
  else
    text = a.format == "json" ? anova_json(anovas).dump(2) + "\n" : a.format == "csv" ? anova_csv(anovas) : anova_markdown(anovas);
  emit(text, a.out);
  return 0;
}

int sensitivity(const Arguments& a) {
  if (a.format != "md" && a.format != "json") throw Error("--format \"" + a.format + "\" (expected md or json)");
  if (a.model.empty()) throw Error("--model MODEL.json is required");
  std::unique_ptr<Model> model = load_model(a.model);
  std::string text;
  if (a.command == "sobol") {
    auto indices = sobol_indices(*model, a.samples, a.seed);
    text = a.format == "json" ? sobol_json(indices).dump(2) + "\n" : sobol_markdown(indices);
  } else {
    auto indices = morris_indices(*model, a.trajectories, a.seed);
    text = a.format == "json" ? morris_json(indices).dump(2) + "\n" : morris_markdown(indices);
  }
  emit(text, a.out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  log::set_program("demcal-analyze");
  Arguments a;
  CLI::App app{
      "demcal-analyze: range analysis and ANOVA of a designed experiment; Sobol and Morris sensitivity of a saved model.\n"
      "  demcal-analyze range|anova --data FILE.csv --factors A,B,... --responses R1,R2 [--error residual|column:NAME]\n"
      "                 [--pool A,B] [--pool-below F] [--format md|json|csv] [--out FILE]\n"
      "  demcal-analyze sobol|morris --model MODEL.json [--samples N | --trajectories R] [--seed S] [--format md|json]",
      "demcal-analyze"};
  app.add_option("command", a.command, "range, anova, sobol or morris")
      ->required()
      ->check(CLI::IsMember({"range", "anova", "sobol", "morris"}));
  app.add_option("--data", a.data, "range/anova: design with responses, .csv or .h5");
  app.add_option("--factors", a.factors, "range/anova: design columns, comma separated (every one is a term)");
  app.add_option("--responses", a.responses, "range/anova: response columns, comma separated");
  app.add_option("--error", a.error, "anova: residual (Minitab GLM) or column:NAME (SS of a blank column)")
      ->capture_default_str();
  app.add_option("--pool", a.pool, "anova: terms pooled into the error, comma separated");
  app.add_option("--pool-below", a.pool_below, "anova: pool terms, smallest first, while their F is below this");
  app.add_option("--model", a.model, "sobol/morris: saved model JSON");
  app.add_option("--samples", a.samples, "sobol: base sample size N (N (k + 2) evaluations)")->capture_default_str();
  app.add_option("--trajectories", a.trajectories, "morris: trajectories r (r (k + 1) evaluations)")->capture_default_str();
  app.add_option("--seed", a.seed, "sobol/morris: seed")->capture_default_str();
  app.add_option("--format", a.format, "md, json or csv")->capture_default_str();
  app.add_option("--out", a.out, "output file (default: stdout)");
  return cli::run_main(app, argc, argv, [&]() {
    bool design = a.command == "range" || a.command == "anova";
    if (design && !a.model.empty()) throw Error("--model applies to sobol and morris, not " + a.command);
    if (!design && (!a.data.empty() || !a.factors.empty() || !a.responses.empty()))
      throw Error(a.command + " works on a saved model (--model); --data/--factors/--responses apply to range and anova");
    return design ? design_analysis(a) : sensitivity(a);
  });
}
