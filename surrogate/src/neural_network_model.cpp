#include "demcal/surrogate/neural_network_model.hpp"

#include <cmath>
#include <utility>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/json_numbers.hpp"
#include "demcal/surrogate/model_file.hpp"

namespace demcal::surrogate {

using nlohmann::json;

NeuralNetworkModel::NeuralNetworkModel(std::vector<InputRange> domain, std::vector<std::string> outputs,
                                       MinMaxScaling input_scaling, MinMaxScaling output_scaling, NeuralNetwork network)
    : BoxModel(std::move(domain), std::move(outputs)), input_scaling_(std::move(input_scaling)),
      output_scaling_(std::move(output_scaling)), network_(std::move(network)) {}

void NeuralNetworkModel::predict(const double* x, double* y) const {
  thread_local std::vector<double> scaled;
  scaled.resize(inputs().size());
  for (std::size_t i = 0; i < inputs().size(); ++i) scaled[i] = input_scaling_.to_unit(static_cast<Eigen::Index>(i), x[i]);
  network_.forward(scaled.data(), y);
  for (std::size_t o = 0; o < outputs().size(); ++o) y[o] = output_scaling_.from_unit(static_cast<Eigen::Index>(o), y[o]);
}

namespace {

Eigen::VectorXd vector_of(const json& array, std::size_t expected, const std::string& origin, const char* what) {
  if (!array.is_array() || array.size() != expected)
    throw Error(origin + ": " + what + " must be an array of " + std::to_string(expected) + " numbers");
  Eigen::VectorXd v(static_cast<Eigen::Index>(expected));
  for (std::size_t i = 0; i < expected; ++i) v(static_cast<Eigen::Index>(i)) = array[i].get<double>();
  return v;
}

json array_of(const Eigen::VectorXd& v) { return json(std::vector<double>(v.data(), v.data() + v.size())); }

json quality_json(const std::vector<OutputQuality>& quality) {
  json r2 = json::object(), rmse = json::object();
  for (const OutputQuality& q : quality) {
    r2[q.output] = json_number(q.r2);
    rmse[q.output] = json_number(q.rmse);
  }
  return {{"r2", r2}, {"rmse", rmse}};
}

}  // namespace

std::unique_ptr<NeuralNetworkModel> NeuralNetworkModel::from_json(const json& file, const std::string& origin) {
  std::vector<InputRange> domain;
  for (const json& input : file.at("inputs"))
    domain.push_back({input.at("name").get<std::string>(), input.at("low").get<double>(), input.at("high").get<double>()});
  std::vector<std::string> outputs = file.at("outputs").get<std::vector<std::string>>();
  const json& net = file.at("network");
  if (net.value("activation", "tanh") != "tanh") throw Error(origin + ": only tanh hidden layers are supported");
  const int hidden = net.at("hidden").get<int>();
  const auto m = domain.size(), o = outputs.size();
  if (hidden <= 0 || m == 0 || o == 0) throw Error(origin + ": network needs inputs, outputs and hidden > 0");
  // Far beyond any fitted network (h = sqrt(m + n) + 10), and the parameter count stays an int.
  if (hidden > 100000) throw Error(origin + ": network.hidden " + std::to_string(hidden) + " is not a fitted network's size");
  NeuralNetwork network(static_cast<int>(m), hidden, static_cast<int>(o));
  network.parameters() =
      vector_of(net.at("parameters"), static_cast<std::size_t>(network.parameter_count()), origin, "network.parameters");
  const json& scaling = file.at("scaling");
  MinMaxScaling in{vector_of(scaling.at("input_min"), m, origin, "scaling.input_min"),
                   vector_of(scaling.at("input_max"), m, origin, "scaling.input_max")};
  MinMaxScaling out{vector_of(scaling.at("output_min"), o, origin, "scaling.output_min"),
                    vector_of(scaling.at("output_max"), o, origin, "scaling.output_max")};
  // Each scaling maps [min, max] onto [-1, 1]: an empty range maps every value to one.
  for (const auto& [scale, what] : {std::pair<const MinMaxScaling*, const char*>{&in, "input"}, {&out, "output"}})
    for (Eigen::Index j = 0; j < scale->min.size(); ++j)
      if (!(scale->min[j] < scale->max[j]) || !std::isfinite(scale->max[j] - scale->min[j]))
        throw Error(origin + ": scaling of " + what + " " + std::to_string(j + 1) + " needs finite min < max");
  return std::make_unique<NeuralNetworkModel>(domain, outputs, in, out, network);
}

json gabp_model_json(const GabpFit& fit, const std::string& data_path) {
  json inputs = json::array();
  for (const InputRange& r : fit.domain) inputs.push_back({{"name", r.name}, {"low", r.low}, {"high", r.high}});
  json trials = json::array();
  for (const HiddenTrial& t : fit.trials)
    trials.push_back({{"hidden", t.hidden}, {"validation_r2", json_number(t.validation_r2)},
                      {"training_mse_scaled", json_number(t.training_mse)}, {"epochs", t.epochs}});
  const GabpOptions& o = fit.options;
  json validation = quality_json(fit.validation);
  validation["method"] = "hold-out";
  validation["rows"] = fit.validation_rows.size();
  json training = quality_json(fit.training);
  training["rows"] = fit.training_rows.size();
  training["ga_best_mse_scaled"] = json_number(fit.ga_best_mse);
  training["lm_epochs"] = fit.epochs;
  training["stop_reason"] = fit.stop_reason;
  return {{"format", kModelFormat},
          {"kind", "gabp"},
          {"data", data_path},
          {"inputs", inputs},
          {"outputs", fit.outputs},
          {"network", {{"hidden", fit.network.hidden()}, {"activation", "tanh"}, {"output_activation", "linear"},
                       {"parameter_layout", "W1 (hidden x inputs, row-major), b1, W2 (outputs x hidden, row-major), b2"},
                       {"parameters", array_of(fit.network.parameters())}}},
          {"scaling", {{"range", "[-1, 1]"},
                       {"input_min", array_of(fit.input_scaling.min)}, {"input_max", array_of(fit.input_scaling.max)},
                       {"output_min", array_of(fit.output_scaling.min)}, {"output_max", array_of(fit.output_scaling.max)}}},
          {"settings", {{"seed", o.seed}, {"validation_fraction", o.validation_fraction},
                        {"hidden", o.hidden == 0 ? json("auto") : json(o.hidden)},
                        {"ga_population", o.ga_population}, {"ga_generations", o.ga_generations},
                        {"ga_weight_bound", o.ga_weight_bound}, {"lm_max_epochs", o.lm_max_epochs},
                        {"lm_max_fail", o.lm_max_fail}}},
          {"training", training},
          {"validation", validation},
          {"validation_rows", fit.validation_rows},
          {"hidden_search", trials}};
}

void register_neural_network_kind() {
  register_model_kind("gabp", [](const json& file, const std::string& origin) -> std::unique_ptr<Model> {
    return NeuralNetworkModel::from_json(file, origin);
  });
}

}  // namespace demcal::surrogate
