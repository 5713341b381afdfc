#pragma once
// The inverse problem: find the micro-parameters x inside bounds whose
// predicted macro values match the targets. Models are seen only through
// demcal::Model; several models may share parameters. A model input is
// either optimised (a parameter of the problem), fixed, or tied to another.
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "demcal/core/model.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/inverse/objective.hpp"
#include "demcal/inverse/optimizer.hpp"

namespace demcal::inverse {

struct Target {
  std::string output;
  double value = 0.0;
};

class InversionProblem {
 public:
  // `space` null: the parameters are the models' inputs, bounded by the
  // intersection of their fitted domains. Otherwise the space's varied
  // parameters that some model uses are optimised within the space's bounds,
  // its fixed and tied values feed the other inputs, and the varied
  // parameters no model uses are reported as free.
  InversionProblem(std::vector<const Model*> models, const ParameterSpace* space, std::vector<Target> targets,
                   ObjectiveKind objective);

  const std::vector<std::string>& parameter_names() const { return names_; }
  const Bounds& bounds() const { return bounds_; }
  const std::vector<Target>& targets() const { return targets_; }
  std::vector<double> target_values() const;
  ObjectiveKind objective_kind() const { return objective_; }
  // Varied parameters of the space that no model uses, with their ranges.
  const std::vector<InputRange>& free_parameters() const { return free_; }
  // Warnings found while setting up (bounds beyond a model's fitted domain).
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The targeted outputs at x, in target order.
  std::vector<double> predict_targets(const Point& x) const;
  // Every output of every model at x.
  std::map<std::string, double> predict_all(const Point& x) const;
  // The 95 % prediction interval of one new run, per output of the models
  // that can give one (response surfaces; not networks or the DEM).
  std::map<std::string, std::pair<double, double>> prediction_intervals_95(const Point& x) const;
  // The objective at x; +infinity where the model gives no finite value.
  double objective(const Point& x) const;
  double objective_of(const std::vector<double>& predicted_targets) const;
  BatchObjective batch_objective() const;

 private:
  struct InputSource {
    int parameter = -1;      // index into x, or -1
    double value = 0.0;      // fixed value when parameter < 0 and factor == 0
    double factor = 0.0;     // tied: factor * x[parameter] + offset
    double offset = 0.0;
    bool tied = false;
  };
  void model_inputs(std::size_t m, const Point& x, std::vector<double>& inputs) const;

  std::vector<const Model*> models_;
  std::vector<std::vector<InputSource>> sources_;  // per model, per input
  std::vector<std::pair<std::size_t, std::size_t>> target_slots_;  // (model, output index)
  std::vector<std::string> names_;
  Bounds bounds_;
  std::vector<Target> targets_;
  ObjectiveKind objective_;
  std::vector<InputRange> free_;
  std::vector<std::string> warnings_;
};

}  // namespace demcal::inverse
