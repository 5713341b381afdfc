#include "demcal/inverse/optimizer.hpp"

#include <cmath>

namespace demcal::inverse {

bool Bounds::contains(const Point& x) const {
  if (x.size() != low.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(x[i] >= low[i] && x[i] <= high[i])) return false;
  return true;
}

EvaluationCounter::EvaluationCounter(BatchObjective objective, const Budget& budget)
    : objective_(std::move(objective)), budget_(budget) {}

std::vector<double> EvaluationCounter::evaluate(const std::vector<Point>& points) {
  std::vector<double> values(points.size(), std::numeric_limits<double>::infinity());
  const long allowed = std::max(0L, std::min<long>(static_cast<long>(points.size()), remaining()));
  if (allowed == 0) return values;
  std::vector<Point> batch(points.begin(), points.begin() + allowed);
  std::vector<double> computed(batch.size());
  objective_(batch, computed);
  for (long i = 0; i < allowed; ++i) {
    double v = std::isnan(computed[static_cast<std::size_t>(i)]) ? std::numeric_limits<double>::infinity()
                                                                 : computed[static_cast<std::size_t>(i)];
    values[static_cast<std::size_t>(i)] = v;
    ++result_.evaluations;
    if (v < result_.value) {
      result_.value = v;
      result_.x = batch[static_cast<std::size_t>(i)];
      result_.history.push_back({result_.evaluations, v});
    }
  }
  return values;
}

double EvaluationCounter::evaluate(const Point& x) { return evaluate(std::vector<Point>{x})[0]; }

RunResult EvaluationCounter::finish(const std::string& stop_reason) {
  result_.stop_reason = stop_reason;
  return result_;
}

std::string budget_stop_reason(const EvaluationCounter& counter, const std::string& otherwise) {
  if (counter.reached_target()) return "objective reached the target";
  if (counter.exhausted()) return "evaluation budget spent";
  return otherwise;
}

}  // namespace demcal::inverse
