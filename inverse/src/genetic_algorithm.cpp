#include "demcal/inverse/genetic_algorithm.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "demcal/core/rng.hpp"

namespace demcal::inverse {

namespace {

// Rank scaling: expectation proportional to 1/sqrt(rank), summing to `parents`.
std::vector<double> rank_expectations(const std::vector<double>& values, int parents) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> expectation(values.size());
  double total = 0.0;
  for (std::size_t r = 0; r < order.size(); ++r) {
    expectation[order[r]] = 1.0 / std::sqrt(static_cast<double>(r + 1));
    total += expectation[order[r]];
  }
  for (double& e : expectation) e *= parents / total;
  return expectation;
}

// Stochastic uniform selection: one random start, equal steps along the
// cumulative expectations.
std::vector<std::size_t> stochastic_uniform(const std::vector<double>& expectation, int parents, Rng& rng) {
  std::vector<std::size_t> chosen;
  double total = std::accumulate(expectation.begin(), expectation.end(), 0.0);
  double step = total / parents;
  double position = rng.uniform() * step;
  double cumulative = 0.0;
  std::size_t i = 0;
  for (int p = 0; p < parents; ++p) {
    while (i + 1 < expectation.size() && cumulative + expectation[i] < position) cumulative += expectation[i++];
    chosen.push_back(i);
    position += step;
  }
  return chosen;
}

}  // namespace

RunResult GeneticAlgorithm::minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                                     const Budget& budget) const {
  const std::size_t n = bounds.size();
  const int N = settings_.population > 0 ? settings_.population : (n <= 5 ? 50 : 200);
  const int elite = std::min(N - 1, static_cast<int>(std::ceil(settings_.elite_fraction * N)));
  const int crossover_kids = static_cast<int>(std::lround(settings_.crossover_fraction * (N - elite)));
  const int mutation_kids = N - elite - crossover_kids;
  const int generations = settings_.max_generations > 0 ? settings_.max_generations : 100 * static_cast<int>(n);
  Rng rng(seed, 0x6a);
  EvaluationCounter counter(objective, budget);

  std::vector<Point> population(static_cast<std::size_t>(N), Point(n));
  for (Point& x : population)
    for (std::size_t j = 0; j < n; ++j) x[j] = rng.uniform(bounds.low[j], bounds.high[j]);
  std::vector<double> values = counter.evaluate(population);
  std::vector<double> best_by_generation{counter.result().value};
  double step = 1.0;  // adaptive-feasible mutation step, as a fraction of the bound width
  std::string reason = "maximum generations";

  for (int g = 1; g <= generations && !counter.should_stop(); ++g) {
    std::vector<std::size_t> order(population.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    const int parents_needed = 2 * crossover_kids + mutation_kids;
    std::vector<std::size_t> parents =
        stochastic_uniform(rank_expectations(values, parents_needed), parents_needed, rng);
    rng.shuffle(parents);

    std::vector<Point> next;
    for (int e = 0; e < elite; ++e) next.push_back(population[order[static_cast<std::size_t>(e)]]);
    std::size_t p = 0;
    for (int k = 0; k < crossover_kids; ++k) {
      const Point& a = population[parents[p++]];
      const Point& b = population[parents[p++]];
      Point child(n);
      for (std::size_t j = 0; j < n; ++j) child[j] = rng.uniform() < 0.5 ? a[j] : b[j];  // scattered
      next.push_back(child);
    }
    for (int k = 0; k < mutation_kids; ++k) {
      // Adaptive feasible: a random direction in the coordinate cone, shortened
      // until the mutant lies inside the bounds.
      const Point& parent = population[parents[p++]];
      Point direction(n, 0.0);
      double norm = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        if (rng.uniform() < 0.5 && n > 1) continue;
        direction[j] = (rng.uniform() < 0.5 ? -1.0 : 1.0) * rng.uniform();
        norm += direction[j] * direction[j];
      }
      if (norm == 0.0) {
        std::size_t j = rng.below(n);
        direction[j] = rng.uniform() < 0.5 ? -1.0 : 1.0;
        norm = 1.0;
      }
      norm = std::sqrt(norm);
      Point mutant = parent;
      double length = step;
      for (int attempt = 0; attempt < 30; ++attempt, length *= 0.5) {
        for (std::size_t j = 0; j < n; ++j)
          mutant[j] = parent[j] + length * (bounds.high[j] - bounds.low[j]) * direction[j] / norm;
        if (bounds.contains(mutant)) break;
        mutant = parent;
      }
      next.push_back(mutant);
    }
    population = std::move(next);
    values = counter.evaluate(population);
    const double best = counter.result().value;
    // The step grows after a generation that improved the best, shrinks otherwise.
    step = best < best_by_generation.back() ? std::min(1.0, step * 4.0) : std::max(1e-12, step / 4.0);
    best_by_generation.push_back(best);
    const int stall = settings_.stall_generations;
    if (static_cast<int>(best_by_generation.size()) > stall) {
      double old = best_by_generation[best_by_generation.size() - 1 - static_cast<std::size_t>(stall)];
      double change = (old - best) / std::max(1.0, std::fabs(best));
      if (change / stall < settings_.function_tolerance) {
        reason = "stall: average relative change over " + std::to_string(stall) + " generations below " +
                 std::to_string(settings_.function_tolerance);
        break;
      }
    }
  }
  return counter.finish(budget_stop_reason(counter, reason));
}

}  // namespace demcal::inverse
