#pragma once
// A saved GA-BP network as a Model, and its JSON form:
//   {"kind": "gabp", "inputs": [{"name","low","high"}], "outputs": [...],
//    "network": {"hidden", "activation": "tanh", "parameters": [...]},
//    "scaling": {"input_min", "input_max", "output_min", "output_max"},
//    "training", "validation", "hidden_search"}
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/core/model.hpp"
#include "demcal/surrogate/gabp.hpp"
#include "demcal/surrogate/neural_network.hpp"

namespace demcal::surrogate {

class NeuralNetworkModel : public BoxModel {
 public:
  NeuralNetworkModel(std::vector<InputRange> domain, std::vector<std::string> outputs, MinMaxScaling input_scaling,
                     MinMaxScaling output_scaling, NeuralNetwork network);
  static std::unique_ptr<NeuralNetworkModel> from_json(const nlohmann::json& file, const std::string& origin);

  void predict(const double* x, double* y) const override;

 private:
  MinMaxScaling input_scaling_, output_scaling_;
  NeuralNetwork network_;
};

nlohmann::json gabp_model_json(const GabpFit& fit, const std::string& data_path);

void register_neural_network_kind();

}  // namespace demcal::surrogate
