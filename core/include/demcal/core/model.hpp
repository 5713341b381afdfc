#pragma once
// What every model of macro values looks like from outside: named inputs in
// natural units, named outputs, the domain it is valid on, and a prediction.
// Response surfaces, networks and the DEM itself (dem::DemModel) implement it, so
// sensitivity analysis and inversion never need to know how a model was made.
#include <string>
#include <vector>

namespace demcal {

struct InputRange {
  std::string name;
  double low = 0.0;
  double high = 0.0;
};

class Model {
 public:
  virtual ~Model() = default;

  virtual const std::vector<std::string>& inputs() const = 0;
  virtual const std::vector<std::string>& outputs() const = 0;
  // The box the model was fitted on, one range per input, in inputs() order.
  virtual const std::vector<InputRange>& domain() const = 0;
  // x: inputs() values in natural units; y: receives outputs() values.
  virtual void predict(const double* x, double* y) const = 0;

  std::vector<double> predict(const std::vector<double>& x) const;
  // The two-sided 95 % prediction interval of one new observation at x (one
  // DEM run on another specimen), per output, into low and high; false when
  // the model cannot say (a network, the DEM itself), as by default.
  virtual bool prediction_interval_95(const double* x, double* low, double* high) const;
  // Several points at once: a DEM-backed model runs them in parallel; the
  // default predicts them one by one. ys[i] receives outputs() values.
  virtual void predict_batch(const std::vector<std::vector<double>>& xs, std::vector<std::vector<double>>& ys) const;
  // Names of the inputs of `x` outside domain() (relative slack `tolerance`
  // of each range's width, so values on a bound count as inside).
  std::vector<std::string> outside_domain(const std::vector<double>& x, double tolerance = 1e-9) const;
};

// A model whose inputs, outputs and domain are set once at construction:
// the usual case, so a subclass only has to predict.
class BoxModel : public Model {
 public:
  BoxModel(std::vector<InputRange> domain, std::vector<std::string> outputs);

  const std::vector<std::string>& inputs() const override { return inputs_; }
  const std::vector<std::string>& outputs() const override { return outputs_; }
  const std::vector<InputRange>& domain() const override { return domain_; }

 private:
  std::vector<InputRange> domain_;
  std::vector<std::string> inputs_;
  std::vector<std::string> outputs_;
};

}  // namespace demcal
