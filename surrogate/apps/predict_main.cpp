// demcal-predict: evaluates a saved model on the rows of a data file.
#include <CLI/CLI.hpp>

#include "demcal/core/cli_main.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/surrogate/data_columns.hpp"
#include "demcal/surrogate/model_file.hpp"
#include "demcal/surrogate/reports.hpp"

namespace {

using namespace demcal;
using namespace demcal::surrogate;

int run(const std::string& model_path, const std::string& data_path, const std::string& out) {
  std::unique_ptr<Model> model = load_model(model_path);
  Table table = cli::read_data(data_path);
  Eigen::MatrixXd X = select_columns(table, model->inputs(), data_path);
  const std::vector<InputRange>& domain = model->domain();
  Table result(table.run_ids());
  std::vector<std::vector<double>> outputs(model->outputs().size(), std::vector<double>(table.rows()));
  std::vector<double> x(model->inputs().size()), y(model->outputs().size());
  int outside = 0;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (std::size_t j = 0; j < x.size(); ++j) x[j] = X(i, static_cast<Eigen::Index>(j));
    std::vector<std::string> names = model->outside_domain(x);
    if (!names.empty()) {
      ++outside;
      std::string detail;
      for (const std::string& name : names) {
        std::size_t j = static_cast<std::size_t>(std::find(model->inputs().begin(), model->inputs().end(), name) -
                                                 model->inputs().begin());
        detail += (detail.empty() ? "" : ", ") + name + " = " + format_number(x[j]) + " not in [" +
                  format_number(domain[j].low) + ", " + format_number(domain[j].high) + "]";
      }
      log::warn("run " + std::to_string(table.run_ids()[static_cast<std::size_t>(i)]) +
                ": outside the fitted domain (" + detail + "); the prediction is an extrapolation");
    }
    model->predict(x.data(), y.data());
    for (std::size_t o = 0; o < y.size(); ++o) outputs[o][static_cast<std::size_t>(i)] = y[o];
  }
  for (std::size_t j = 0; j < x.size(); ++j) result.add_column(model->inputs()[j], table.column(model->inputs()[j]));
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    if (result.has_column(model->outputs()[o])) throw Error("output " + model->outputs()[o] + " is also an input column");
    result.add_column(model->outputs()[o], outputs[o]);
  }
  result.write(out, "/predictions");
  log::info("wrote " + std::to_string(table.rows()) + " predictions to " + out +
            (outside > 0 ? " (" + std::to_string(outside) + " outside the fitted domain)" : ""));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  log::set_program("demcal-predict");
  std::string model, data, out;
  bool quiet = false;
  CLI::App app{"demcal-predict: evaluates a saved model (demcal-fit) on every row of a data file.\n"
               "  demcal-predict --model MODEL.json --data FILE.csv --out OUT.csv",
               "demcal-predict"};
  app.add_option("--model", model, "model JSON written by demcal-fit")->required();
  app.add_option("--data", data, "rows to predict: a column per model input, .csv or .h5")->required();
  app.add_option("--out", out, "predictions: the input columns plus one column per output, .csv or .h5")->required();
  app.add_flag("--quiet", quiet, "no summary line (domain warnings are still printed)");
  return cli::run_main(app, argc, argv, [&]() {
    if (quiet) log::set_level(log::Level::Quiet);
    return run(model, data, out);
  });
}
