#include "demcal/inverse/objective.hpp"

#include <cmath>

#include "demcal/core/error.hpp"

namespace demcal::inverse {

std::vector<std::string> objective_names() { return {"sum-rel", "max-rel", "sse-rel", "minimise"}; }

ObjectiveKind parse_objective(const std::string& name) {
  if (name == "sum-rel") return ObjectiveKind::SumRel;
  if (name == "max-rel") return ObjectiveKind::MaxRel;
  if (name == "sse-rel") return ObjectiveKind::SseRel;
  if (name == "minimise") return ObjectiveKind::Minimise;
  throw Error("--objective \"" + name + "\" (expected sum-rel, max-rel, sse-rel or minimise)");
}

std::string to_string(ObjectiveKind kind) {
  switch (kind) {
    case ObjectiveKind::SumRel: return "sum-rel";
    case ObjectiveKind::MaxRel: return "max-rel";
    case ObjectiveKind::SseRel: return "sse-rel";
    case ObjectiveKind::Minimise: return "minimise";
  }
  return "";
}

double relative_objective(ObjectiveKind kind, const std::vector<double>& predicted, const std::vector<double>& targets) {
  double total = 0.0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    // No prediction (a failed DEM run) is infinitely far; std::max would drop a NaN.
    if (!std::isfinite(predicted[i])) return std::numeric_limits<double>::infinity();
    double e = (predicted[i] - targets[i]) / std::fabs(targets[i]);
    if (kind == ObjectiveKind::Minimise) total += predicted[i] / std::fabs(targets[i]);
    else if (kind == ObjectiveKind::SumRel) total += std::fabs(e);
    else if (kind == ObjectiveKind::MaxRel) total = std::max(total, std::fabs(e));
    else total += e * e;
  }
  return std::isnan(total) ? std::numeric_limits<double>::infinity() : total;
}

double max_relative_error(const std::vector<double>& predicted, const std::vector<double>& targets) {
  return relative_objective(ObjectiveKind::MaxRel, predicted, targets);
}

}  // namespace demcal::inverse
