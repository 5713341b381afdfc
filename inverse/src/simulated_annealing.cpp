#include "demcal/inverse/simulated_annealing.hpp"

#include <algorithm>
#include <cmath>

#include "demcal/core/rng.hpp"

namespace demcal::inverse {

namespace {

// One coordinate's new value strictly inside (low, high), redrawn until it is.
double perturb(double x, double low, double high, double t, bool vfsr, double scale, Rng& rng) {
  const double width = high - low;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    double step;
    if (vfsr) {
      double u = rng.uniform();
      double sign = u < 0.5 ? -1.0 : 1.0;
      step = sign * t * (std::pow(1.0 + 1.0 / t, std::fabs(2.0 * u - 1.0)) - 1.0);
    } else {
      step = scale * t * rng.cauchy();
    }
    double candidate = x + width * step;
    if (candidate > low && candidate < high) return candidate;
  }
  return x;  // practically unreachable: keep the old value rather than leave the box
}

}  // namespace

RunResult SimulatedAnnealing::minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                                       const Budget& budget) const {
  const std::size_t n = bounds.size();
  Rng rng(seed, settings_.vfsr ? 0x5af5 : 0x5a);
  EvaluationCounter counter(objective, budget);
  Point x(n);
  for (std::size_t j = 0; j < n; ++j) x[j] = rng.uniform(bounds.low[j], bounds.high[j]);
  // Keep the start strictly inside (the DEM cannot run on some bounds, e.g. zero stiffness).
  for (std::size_t j = 0; j < n; ++j)
    if (!(x[j] > bounds.low[j])) x[j] = 0.5 * (bounds.low[j] + bounds.high[j]);
  double energy = counter.evaluate(x);
  std::string reason = "budget";
  for (long k = 0; !counter.should_stop(); ++k) {
    const double temperature =
        settings_.initial_temperature * std::pow(settings_.cooling, static_cast<double>(k) / static_cast<double>(n));
    const double t = temperature / settings_.initial_temperature;  // relative temperature, 1 at the start
    if (t < 1e-300) {
      reason = "temperature underflow";
      break;
    }
    for (int trial = 0; trial < settings_.markov_chain_length && !counter.should_stop(); ++trial) {
      // One candidate (the paper's chain), or several evaluated together of
      // which the best faces the Metropolis test (a DEM runs them in parallel).
      std::vector<Point> candidates(static_cast<std::size_t>(settings_.parallel_trials), x);
      for (Point& candidate : candidates)
        for (std::size_t j = 0; j < n; ++j)
          candidate[j] = perturb(x[j], bounds.low[j], bounds.high[j], t, settings_.vfsr, settings_.step_scale, rng);
      std::vector<double> energies = counter.evaluate(candidates);
      const std::size_t best = static_cast<std::size_t>(std::min_element(energies.begin(), energies.end()) - energies.begin());
      double delta = energies[best] - energy;
      if (delta < 0 || rng.uniform() < std::exp(-delta / temperature)) {
        x = candidates[best];
        energy = energies[best];
      }
    }
  }
  return counter.finish(budget_stop_reason(counter, reason));
}

}  // namespace demcal::inverse
