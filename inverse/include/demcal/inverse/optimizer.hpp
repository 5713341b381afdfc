#pragma once
// What every optimiser of the inversion stage shares: a batch objective (a
// whole population at once, so DEM-backed objectives can run it in
// parallel), box bounds, a budget, and a record of the best value against
// the number of evaluations (the convergence curve).
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace demcal::inverse {

using Point = std::vector<double>;

// Fills values[i] with the objective at points[i].
using BatchObjective = std::function<void(const std::vector<Point>& points, std::vector<double>& values)>;

struct Bounds {
  Point low, high;
  std::size_t size() const { return low.size(); }
  bool contains(const Point& x) const;
};

struct Budget {
  long max_evaluations = 100000;
  // Stop as soon as the best value is at or below this.
  double target_value = -std::numeric_limits<double>::infinity();
};

struct HistoryPoint {
  long evaluations = 0;
  double best = 0.0;
};

struct RunResult {
  Point x;
  double value = std::numeric_limits<double>::infinity();
  long evaluations = 0;
  std::string stop_reason;
  std::vector<HistoryPoint> history;  // one entry per improvement of the best
};

// Counts evaluations, keeps the best point and the convergence record, and
// says when the budget is spent. Every optimiser evaluates through it.
class EvaluationCounter {
 public:
  EvaluationCounter(BatchObjective objective, const Budget& budget);

  // Evaluates as many of `points` as the budget allows; the values of points
  // past the budget are +infinity.
  std::vector<double> evaluate(const std::vector<Point>& points);
  double evaluate(const Point& x);

  bool exhausted() const { return result_.evaluations >= budget_.max_evaluations; }
  bool reached_target() const { return result_.value <= budget_.target_value; }
  bool should_stop() const { return exhausted() || reached_target(); }
  long remaining() const { return budget_.max_evaluations - result_.evaluations; }
  const RunResult& result() const { return result_; }
  RunResult finish(const std::string& stop_reason);

 private:
  BatchObjective objective_;
  Budget budget_;
  RunResult result_;
};

// Text for a stop caused by the budget or the target, or `otherwise`.
std::string budget_stop_reason(const EvaluationCounter& counter, const std::string& otherwise);

class Optimizer {
 public:
  virtual ~Optimizer() = default;
  virtual std::string name() const = 0;
  virtual RunResult minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                             const Budget& budget) const = 0;
};

// Settings by name ("population", "generations", ...); each optimiser reads
// the ones it knows and the registry rejects the others.
using Settings = std::map<std::string, double>;

// The optimisers by name: ga, sa, sa-vfsr, wca, lhs-wca, hs. Unknown names and
// unknown settings are errors listing the known ones.
std::unique_ptr<Optimizer> make_optimizer(const std::string& name, const Settings& settings);
std::vector<std::string> optimizer_names();

}  // namespace demcal::inverse
