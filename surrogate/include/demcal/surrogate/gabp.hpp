#pragma once
// The GA-BP surrogate of He et al. (2019): a genetic algorithm searches the
// initial weights and biases of a one-hidden-layer network on the training
// MSE, then Levenberg-Marquardt trains it with early stopping on a held-out
// validation split. The hidden size is fixed or chosen as
// h = round(sqrt(m + n)) + a, a = 1..10, by validation R^2.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demcal/core/model.hpp"
#include "demcal/surrogate/neural_network.hpp"

namespace demcal::surrogate {

struct GabpOptions {
  int hidden = 0;                    // 0: automatic search
  double validation_fraction = 0.25; // held out for early stopping and R^2
  std::uint64_t seed = 1;
  int ga_population = 40;
  int ga_generations = 40;
  double ga_weight_bound = 2.0;      // initial weights searched in [-bound, bound]
  int lm_max_epochs = 1000;
  int lm_max_fail = 6;               // epochs without validation improvement before stopping
  bool progress = false;             // one line per tried hidden size on stderr
};

struct OutputQuality {
  std::string output;
  double r2 = 0.0;
  double rmse = 0.0;
};

struct HiddenTrial {
  int hidden = 0;
  double validation_r2 = 0.0;  // mean over outputs
  double training_mse = 0.0;   // scaled units
  int epochs = 0;
};

struct GabpFit {
  std::vector<std::string> inputs, outputs;
  std::vector<InputRange> domain;
  MinMaxScaling input_scaling, output_scaling;
  NeuralNetwork network{1, 1, 1};
  std::vector<int> training_rows, validation_rows;  // 0-based data rows
  std::vector<OutputQuality> training, validation;
  std::vector<HiddenTrial> trials;
  double ga_best_mse = 0.0;    // scaled training MSE after the GA
  int epochs = 0;
  std::string stop_reason;
  GabpOptions options;
};

GabpFit fit_gabp(const std::vector<std::string>& inputs, const Eigen::MatrixXd& X,
                 const std::vector<std::string>& outputs, const Eigen::MatrixXd& Y, const GabpOptions& options);

// R^2 and RMSE of predictions against observations, per column.
std::vector<OutputQuality> prediction_quality(const std::vector<std::string>& names, const Eigen::MatrixXd& observed,
                                              const Eigen::MatrixXd& predicted);

}  // namespace demcal::surrogate
