#pragma once
// A feed-forward network with one tanh hidden layer and linear outputs, on
// inputs and outputs scaled to [-1, 1] (MATLAB's mapminmax convention).
// Parameters live in one vector so that the genetic algorithm and the
// Levenberg-Marquardt trainer work on the same thing:
//   [W1 (hidden x inputs, row-major) | b1 (hidden) | W2 (outputs x hidden, row-major) | b2 (outputs)]
#include <vector>

#include <Eigen/Dense>

namespace demcal::surrogate {

// Affine map of each column between [min, max] and [-1, 1].
struct MinMaxScaling {
  Eigen::VectorXd min, max;

  static MinMaxScaling of_columns(const Eigen::MatrixXd& data);
  double to_unit(Eigen::Index j, double value) const;    // natural -> [-1, 1]
  double from_unit(Eigen::Index j, double value) const;  // [-1, 1] -> natural
  Eigen::MatrixXd to_unit(const Eigen::MatrixXd& data) const;
};

class NeuralNetwork {
 public:
  NeuralNetwork(int inputs, int hidden, int outputs);

  int inputs() const { return inputs_; }
  int hidden() const { return hidden_; }
  int outputs() const { return outputs_; }
  static int parameter_count(int inputs, int hidden, int outputs) { return hidden * (inputs + 1) + outputs * (hidden + 1); }
  int parameter_count() const { return parameter_count(inputs_, hidden_, outputs_); }

  Eigen::VectorXd& parameters() { return parameters_; }
  const Eigen::VectorXd& parameters() const { return parameters_; }

  // Scaled inputs -> scaled outputs.
  void forward(const double* x, double* y) const;
  Eigen::MatrixXd forward(const Eigen::MatrixXd& X) const;  // rows are samples

  // Residuals r = forward(X) - Y stacked sample by sample (outputs fastest)
  // and their Jacobian with respect to parameters().
  void residuals_and_jacobian(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, Eigen::VectorXd& r,
                              Eigen::MatrixXd& J) const;

 private:
  int inputs_, hidden_, outputs_;
  Eigen::VectorXd parameters_;
};

}  // namespace demcal::surrogate
