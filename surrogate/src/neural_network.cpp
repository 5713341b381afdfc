#include "demcal/surrogate/neural_network.hpp"

#include <cmath>

namespace demcal::surrogate {

MinMaxScaling MinMaxScaling::of_columns(const Eigen::MatrixXd& data) {
  return {data.colwise().minCoeff().transpose(), data.colwise().maxCoeff().transpose()};
}

double MinMaxScaling::to_unit(Eigen::Index j, double value) const {
  double width = max(j) - min(j);
  return width > 0 ? 2.0 * (value - min(j)) / width - 1.0 : 0.0;
}

double MinMaxScaling::from_unit(Eigen::Index j, double value) const {
  return min(j) + 0.5 * (value + 1.0) * (max(j) - min(j));
}

Eigen::MatrixXd MinMaxScaling::to_unit(const Eigen::MatrixXd& data) const {
  Eigen::MatrixXd out(data.rows(), data.cols());
  for (Eigen::Index i = 0; i < data.rows(); ++i)
    for (Eigen::Index j = 0; j < data.cols(); ++j) out(i, j) = to_unit(j, data(i, j));
  return out;
}

NeuralNetwork::NeuralNetwork(int inputs, int hidden, int outputs)
    : inputs_(inputs), hidden_(hidden), outputs_(outputs),
      parameters_(Eigen::VectorXd::Zero(parameter_count(inputs, hidden, outputs))) {}

void NeuralNetwork::forward(const double* x, double* y) const {
  const double* w1 = parameters_.data();
  const double* b1 = w1 + hidden_ * inputs_;
  const double* w2 = b1 + hidden_;
  const double* b2 = w2 + outputs_ * hidden_;
  // Small fixed-size scratch would need a bound; hidden sizes are small, so a
  // thread-local buffer avoids a heap allocation per call.
  thread_local std::vector<double> a;
  a.resize(static_cast<std::size_t>(hidden_));
  for (int h = 0; h < hidden_; ++h) {
    double z = b1[h];
    for (int i = 0; i < inputs_; ++i) z += w1[h * inputs_ + i] * x[i];
    a[static_cast<std::size_t>(h)] = std::tanh(z);
  }
  for (int o = 0; o < outputs_; ++o) {
    double v = b2[o];
    for (int h = 0; h < hidden_; ++h) v += w2[o * hidden_ + h] * a[static_cast<std::size_t>(h)];
    y[o] = v;
  }
}

Eigen::MatrixXd NeuralNetwork::forward(const Eigen::MatrixXd& X) const {
  Eigen::MatrixXd Y(X.rows(), outputs_);
  std::vector<double> x(static_cast<std::size_t>(inputs_)), y(static_cast<std::size_t>(outputs_));
  for (Eigen::Index s = 0; s < X.rows(); ++s) {
    for (int i = 0; i < inputs_; ++i) x[static_cast<std::size_t>(i)] = X(s, i);
    forward(x.data(), y.data());
    for (int o = 0; o < outputs_; ++o) Y(s, o) = y[static_cast<std::size_t>(o)];
  }
  return Y;
}

void NeuralNetwork::residuals_and_jacobian(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, Eigen::VectorXd& r,
                                           Eigen::MatrixXd& J) const {
  const Eigen::Index samples = X.rows();
  const int P = parameter_count();
  r.resize(samples * outputs_);
  J.setZero(samples * outputs_, P);
  const double* w1 = parameters_.data();
  const double* b1 = w1 + hidden_ * inputs_;
  const double* w2 = b1 + hidden_;
  const double* b2 = w2 + outputs_ * hidden_;
  const int off_b1 = hidden_ * inputs_, off_w2 = off_b1 + hidden_, off_b2 = off_w2 + outputs_ * hidden_;
  std::vector<double> a(static_cast<std::size_t>(hidden_));
  for (Eigen::Index s = 0; s < samples; ++s) {
    for (int h = 0; h < hidden_; ++h) {
      double z = b1[h];
      for (int i = 0; i < inputs_; ++i) z += w1[h * inputs_ + i] * X(s, i);
      a[static_cast<std::size_t>(h)] = std::tanh(z);
    }
    for (int o = 0; o < outputs_; ++o) {
      const Eigen::Index row = s * outputs_ + o;
      double v = b2[o];
      for (int h = 0; h < hidden_; ++h) v += w2[o * hidden_ + h] * a[static_cast<std::size_t>(h)];
      r(row) = v - Y(s, o);
      J(row, off_b2 + o) = 1.0;
      for (int h = 0; h < hidden_; ++h) {
        double ah = a[static_cast<std::size_t>(h)];
        J(row, off_w2 + o * hidden_ + h) = ah;
        double back = w2[o * hidden_ + h] * (1.0 - ah * ah);  // d v / d z_h
        J(row, off_b1 + h) = back;
        for (int i = 0; i < inputs_; ++i) J(row, h * inputs_ + i) = back * X(s, i);
      }
    }
  }
}

}  // namespace demcal::surrogate
