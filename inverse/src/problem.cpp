#include "demcal/inverse/problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::inverse {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

InversionProblem::InversionProblem(std::vector<const Model*> models, const ParameterSpace* space,
                                   std::vector<Target> targets, ObjectiveKind objective)
    : models_(std::move(models)), targets_(std::move(targets)), objective_(objective) {
  if (models_.empty()) throw Error("invert: no model given (--model MODEL.json)");
  if (targets_.empty()) throw Error("invert: no target given (--target NAME=VALUE)");

  // Which model predicts each target.
  std::vector<std::string> all_outputs;
  for (const Model* m : models_)
    for (const std::string& o : m->outputs()) all_outputs.push_back(o);
  std::set<std::string> seen_targets;
  for (const Target& t : targets_) {
    if (!seen_targets.insert(t.output).second) throw Error("--target " + t.output + " is given twice");
    if (!std::isfinite(t.value) || t.value == 0.0)
      throw Error("--target " + t.output + "=" + format_double(t.value) + ": a target must be finite and non-zero (errors are relative to it)");
    int found = 0;
    for (std::size_t m = 0; m < models_.size(); ++m) {
      const auto& outs = models_[m]->outputs();
      auto it = std::find(outs.begin(), outs.end(), t.output);
      if (it == outs.end()) continue;
      if (found++ == 0) target_slots_.push_back({m, static_cast<std::size_t>(it - outs.begin())});
    }
    if (found == 0) throw Error("--target " + t.output + ": no model predicts it (outputs: " + joined(all_outputs) + ")");
    if (found > 1) throw Error("--target " + t.output + ": more than one model predicts it; give one model per output");
  }

  // A model that predicts no target has no say: leave it out, so parameters
  // only it uses are not given values the targets never constrained.
  {
    std::vector<const Model*> used;
    std::vector<std::pair<std::size_t, std::size_t>> slots;
    std::vector<std::size_t> renumber(models_.size(), models_.size());
    for (auto [m, o] : target_slots_) {
      if (renumber[m] == models_.size()) {
        renumber[m] = used.size();
        used.push_back(models_[m]);
      }
      slots.push_back({renumber[m], o});
    }
    for (std::size_t m = 0; m < models_.size(); ++m)
      if (renumber[m] == models_.size()) {
        std::string outs;
        for (const std::string& o : models_[m]->outputs()) outs += (outs.empty() ? "" : ", ") + o;
        warnings_.push_back("a model of " + outs + " predicts no targeted output: left out of the inversion");
      }
    models_ = used;
    target_slots_ = slots;
  }

  // Every input any model needs, in order of first appearance.
  std::vector<std::string> inputs;
  for (const Model* m : models_)
    for (const std::string& in : m->inputs())
      if (std::find(inputs.begin(), inputs.end(), in) == inputs.end()) inputs.push_back(in);

  auto domain_of = [&](const std::string& name, double& low, double& high) {
    low = -std::numeric_limits<double>::infinity();
    high = std::numeric_limits<double>::infinity();
    for (const Model* m : models_)
      for (const InputRange& r : m->domain())
        if (r.name == name) {
          low = std::max(low, r.low);
          high = std::min(high, r.high);
        }
  };

  if (!space) {
    for (const std::string& in : inputs) {
      double low, high;
      domain_of(in, low, high);
      if (!(low <= high))
        throw Error("invert: the models' fitted domains of " + in + " do not overlap; give --space with bounds");
      names_.push_back(in);
      bounds_.low.push_back(low);
      bounds_.high.push_back(high);
    }
  } else {
    // Varied parameters used by a model (directly or as a tie's source), in the space's order.
    std::set<std::string> needed;
    for (const std::string& in : inputs) {
      if (space->contains(in)) {
        needed.insert(in);
        continue;
      }
      if (space->fixed().count(in)) continue;
      auto tie = std::find_if(space->tied().begin(), space->tied().end(), [&](const TiedParameter& t) { return t.name == in; });
      if (tie == space->tied().end())
        throw Error("invert: model input " + in + " is neither varied, fixed nor tied in the space");
      if (space->contains(tie->source)) needed.insert(tie->source);
    }
    for (const Parameter& p : space->parameters()) {
      if (needed.count(p.name)) {
        names_.push_back(p.name);
        bounds_.low.push_back(p.low);
        bounds_.high.push_back(p.high);
        double low, high;
        domain_of(p.name, low, high);
        if (p.low < low || p.high > high)
          warnings_.push_back("the space's range of " + p.name + " [" + format_double(p.low) + ", " + format_double(p.high) +
                              "] goes beyond a model's fitted domain [" + format_double(low) + ", " + format_double(high) +
                              "]: predictions there are extrapolations");
      } else {
        free_.push_back({p.name, p.low, p.high});
      }
    }
  }

  auto parameter_index = [&](const std::string& name) {
    auto it = std::find(names_.begin(), names_.end(), name);
    return it == names_.end() ? -1 : static_cast<int>(it - names_.begin());
  };
  for (const Model* m : models_) {
    std::vector<InputSource> sources;
    for (const std::string& in : m->inputs()) {
      InputSource s;
      s.parameter = parameter_index(in);
      if (s.parameter < 0 && space) {
        if (space->fixed().count(in)) {
          s.value = space->fixed().at(in);
        } else {
          const TiedParameter& tie = *std::find_if(space->tied().begin(), space->tied().end(),
                                                   [&](const TiedParameter& t) { return t.name == in; });
          s.tied = true;
          s.factor = tie.factor;
          s.offset = tie.offset;
          s.parameter = parameter_index(tie.source);
          if (s.parameter < 0) {
            if (!space->fixed().count(tie.source))
              throw Error("invert: " + in + " is tied to " + tie.source + ", which is neither varied nor fixed");
            s.tied = false;
            s.value = tie.factor * space->fixed().at(tie.source) + tie.offset;
          }
        }
      }
      sources.push_back(s);
    }
    sources_.push_back(sources);
  }
  for (std::size_t j = 0; j < names_.size(); ++j)
    if (!(bounds_.low[j] < bounds_.high[j]))
      throw Error("invert: parameter " + names_[j] + " has an empty range [" + format_double(bounds_.low[j]) + ", " +
                  format_double(bounds_.high[j]) + "]");
}

std::vector<double> InversionProblem::target_values() const {
  std::vector<double> values;
  for (const Target& t : targets_) values.push_back(t.value);
  return values;
}

void InversionProblem::model_inputs(std::size_t m, const Point& x, std::vector<double>& inputs) const {
  const std::vector<InputSource>& sources = sources_[m];
  inputs.resize(sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const InputSource& s = sources[i];
    if (s.tied)
      inputs[i] = s.factor * x[static_cast<std::size_t>(s.parameter)] + s.offset;
    else if (s.parameter >= 0)
      inputs[i] = x[static_cast<std::size_t>(s.parameter)];
    else
      inputs[i] = s.value;
  }
}

std::vector<double> InversionProblem::predict_targets(const Point& x) const {
  std::vector<std::vector<double>> outputs(models_.size());
  std::vector<double> inputs;
  std::vector<double> predicted;
  for (auto [m, o] : target_slots_) {
    if (outputs[m].empty()) {
      model_inputs(m, x, inputs);
      outputs[m].resize(models_[m]->outputs().size());
      models_[m]->predict(inputs.data(), outputs[m].data());
    }
    predicted.push_back(outputs[m][o]);
  }
  return predicted;
}

std::map<std::string, double> InversionProblem::predict_all(const Point& x) const {
  std::map<std::string, double> all;
  std::vector<double> inputs;
  for (std::size_t m = 0; m < models_.size(); ++m) {
    model_inputs(m, x, inputs);
    std::vector<double> y(models_[m]->outputs().size());
    models_[m]->predict(inputs.data(), y.data());
    for (std::size_t o = 0; o < y.size(); ++o) all.emplace(models_[m]->outputs()[o], y[o]);
  }
  return all;
}

std::map<std::string, std::pair<double, double>> InversionProblem::prediction_intervals_95(const Point& x) const {
  std::map<std::string, std::pair<double, double>> all;
  std::vector<double> inputs;
  for (std::size_t m = 0; m < models_.size(); ++m) {
    model_inputs(m, x, inputs);
    const std::size_t n = models_[m]->outputs().size();
    std::vector<double> low(n), high(n);
    if (!models_[m]->prediction_interval_95(inputs.data(), low.data(), high.data())) continue;
    for (std::size_t o = 0; o < n; ++o) all.emplace(models_[m]->outputs()[o], std::make_pair(low[o], high[o]));
  }
  return all;
}

double InversionProblem::objective(const Point& x) const { return objective_of(predict_targets(x)); }

double InversionProblem::objective_of(const std::vector<double>& predicted) const {
  double value = relative_objective(objective_, predicted, target_values());
  // A point the model cannot predict (a failed DEM run) is never a solution.
  return std::isfinite(value) ? value : std::numeric_limits<double>::infinity();
}

BatchObjective InversionProblem::batch_objective() const {
  return [this](const std::vector<Point>& points, std::vector<double>& values) {
    // Each model predicts the whole batch at once (a DEM model runs it in parallel).
    std::vector<std::vector<std::vector<double>>> outputs(models_.size());
    std::vector<bool> needed(models_.size(), false);
    for (auto [m, o] : target_slots_) needed[m] = true;
    for (std::size_t m = 0; m < models_.size(); ++m) {
      if (!needed[m]) continue;
      std::vector<std::vector<double>> inputs(points.size());
      for (std::size_t i = 0; i < points.size(); ++i) model_inputs(m, points[i], inputs[i]);
      models_[m]->predict_batch(inputs, outputs[m]);
    }
    values.resize(points.size());
    std::vector<double> predicted;
    for (std::size_t i = 0; i < points.size(); ++i) {
      predicted.clear();
      for (auto [m, o] : target_slots_) predicted.push_back(outputs[m][i][o]);
      values[i] = objective_of(predicted);
    }
  };
}

}  // namespace demcal::inverse
