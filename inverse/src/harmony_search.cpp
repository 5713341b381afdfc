#include "demcal/inverse/harmony_search.hpp"

#include <algorithm>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"

namespace demcal::inverse {

RunResult HarmonySearch::minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                                  const Budget& budget) const {
  const HsSettings& s = settings_;
  const std::size_t n = bounds.size();
  const std::size_t hms = static_cast<std::size_t>(s.memory_size);
  Rng rng(seed, 0x6873 /* "hs" */);
  EvaluationCounter counter(objective, budget);

  std::vector<Point> memory(hms, Point(n));
  for (Point& x : memory)
    for (std::size_t j = 0; j < n; ++j) x[j] = rng.uniform(bounds.low[j], bounds.high[j]);
  std::vector<double> cost = counter.evaluate(memory);

  // The schedule runs over the iterations the budget leaves after the first memory.
  const long iterations =
      std::max(1L, (budget.max_evaluations - static_cast<long>(hms)) / static_cast<long>(s.improvisations));
  for (long it = 0; !counter.should_stop(); ++it) {
    const double progress = std::min(1.0, static_cast<double>(it) / static_cast<double>(iterations));
    const double par = s.par_min + (s.par_max - s.par_min) * progress;
    const double bandwidth = s.bandwidth_max * std::exp(std::log(s.bandwidth_min / s.bandwidth_max) * progress);
    const long count = std::min<long>(s.improvisations, counter.remaining());
    std::vector<Point> fresh(static_cast<std::size_t>(count), Point(n));
    for (Point& x : fresh)
      for (std::size_t j = 0; j < n; ++j) {
        const double range = bounds.high[j] - bounds.low[j];
        if (rng.uniform() < s.hmcr) {
          x[j] = memory[static_cast<std::size_t>(rng.below(hms))][j];
          if (rng.uniform() < par) x[j] += (2 * rng.uniform() - 1) * bandwidth * range;
          x[j] = std::clamp(x[j], bounds.low[j], bounds.high[j]);
        } else {
          x[j] = rng.uniform(bounds.low[j], bounds.high[j]);
        }
      }
    const std::vector<double> values = counter.evaluate(fresh);
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      const std::size_t worst = static_cast<std::size_t>(std::max_element(cost.begin(), cost.end()) - cost.begin());
      if (values[k] < cost[worst]) {
        memory[worst] = fresh[k];
        cost[worst] = values[k];
      }
    }
  }
  return counter.finish(budget_stop_reason(counter, "budget spent"));
}

}  // namespace demcal::inverse
