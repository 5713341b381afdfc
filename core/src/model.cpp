#include "demcal/core/model.hpp"

#include "demcal/core/error.hpp"

namespace demcal {

std::vector<double> Model::predict(const std::vector<double>& x) const {
  if (x.size() != inputs().size())
    throw Error("model expects " + std::to_string(inputs().size()) + " inputs, got " + std::to_string(x.size()));
  std::vector<double> y(outputs().size());
  predict(x.data(), y.data());
  return y;
}

bool Model::prediction_interval_95(const double*, double*, double*) const { return false; }

void Model::predict_batch(const std::vector<std::vector<double>>& xs, std::vector<std::vector<double>>& ys) const {
  ys.resize(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) ys[i] = predict(xs[i]);
}

std::vector<std::string> Model::outside_domain(const std::vector<double>& x, double tolerance) const {
  std::vector<std::string> outside;
  const std::vector<InputRange>& box = domain();
  for (std::size_t i = 0; i < box.size() && i < x.size(); ++i) {
    double slack = tolerance * (box[i].high - box[i].low);
    if (!(x[i] >= box[i].low - slack && x[i] <= box[i].high + slack)) outside.push_back(box[i].name);
  }
  return outside;
}

BoxModel::BoxModel(std::vector<InputRange> domain, std::vector<std::string> outputs)
    : domain_(std::move(domain)), outputs_(std::move(outputs)) {
  for (const InputRange& r : domain_) inputs_.push_back(r.name);
}

}  // namespace demcal
