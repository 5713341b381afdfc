#include "demcal/inverse/water_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/doe/space_filling.hpp"

namespace demcal::inverse {

namespace {

double distance(const Point& a, const Point& b) {
  double d = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) d += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(d);
}

void clip(Point& x, const Bounds& bounds) {
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = std::clamp(x[j], bounds.low[j], bounds.high[j]);
}

Point random_point(const Bounds& bounds, Rng& rng) {
  Point x(bounds.size());
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = rng.uniform(bounds.low[j], bounds.high[j]);
  return x;
}

}  // namespace

RunResult WaterCycle::minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                               const Budget& budget) const {
  const std::size_t n = bounds.size();
  const int N = settings_.population;
  const int nsr = settings_.rivers_and_sea;
  if (N < nsr + 1 || nsr < 1) throw Error("wca: the population must exceed Nsr (sea + rivers) and Nsr >= 1");
  const int n_streams = N - nsr;
  const long iterations = settings_.max_iterations > 0 ? settings_.max_iterations : std::max(1L, budget.max_evaluations / N);
  Rng rng(seed, settings_.latin_hypercube_start ? 0x1c5 : 0xc5);
  EvaluationCounter counter(objective, budget);

  std::vector<Point> population;
  if (settings_.latin_hypercube_start) {
    doe::LhsOptions lhs;
    lhs.runs = N;
    lhs.factors = static_cast<int>(n);
    lhs.seed = seed;
    Eigen::MatrixXd unit = doe::latin_hypercube(lhs).coded;
    for (int i = 0; i < N; ++i) {
      Point x(n);
      for (std::size_t j = 0; j < n; ++j)
        x[j] = bounds.low[j] + unit(i, static_cast<Eigen::Index>(j)) * (bounds.high[j] - bounds.low[j]);
      population.push_back(x);
    }
  } else {
    for (int i = 0; i < N; ++i) population.push_back(random_point(bounds, rng));
  }
  std::vector<double> cost = counter.evaluate(population);
  std::vector<std::size_t> order(static_cast<std::size_t>(N));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] < cost[b]; });
  // rivers[0] is the sea; streams flow into the river (or sea) they are assigned to.
  std::vector<Point> rivers, streams;
  std::vector<double> river_cost, stream_cost;
  for (int i = 0; i < nsr; ++i) {
    rivers.push_back(population[order[static_cast<std::size_t>(i)]]);
    river_cost.push_back(cost[order[static_cast<std::size_t>(i)]]);
  }
  for (int i = nsr; i < N; ++i) {
    streams.push_back(population[order[static_cast<std::size_t>(i)]]);
    stream_cost.push_back(cost[order[static_cast<std::size_t>(i)]]);
  }
  // Streams per river in proportion to how much better it is than the best stream
  // (the authors' intensity rule); every river gets at least one, the sea the rest.
  std::vector<int> owner(static_cast<std::size_t>(n_streams), 0);
  {
    std::vector<double> strength(static_cast<std::size_t>(nsr));
    double total = 0.0;
    for (int i = 0; i < nsr; ++i) {
      strength[static_cast<std::size_t>(i)] = std::fabs(river_cost[static_cast<std::size_t>(i)] - stream_cost[0]);
      total += strength[static_cast<std::size_t>(i)];
    }
    std::vector<int> count(static_cast<std::size_t>(nsr), 1);
    for (int i = 0; i < nsr; ++i)
      if (total > 0)
        count[static_cast<std::size_t>(i)] = std::max(
            1, static_cast<int>(std::lround(strength[static_cast<std::size_t>(i)] / total * n_streams)));
    // The sea takes what the rivers leave; shrink the largest shares until the counts add up.
    count[0] = n_streams - std::accumulate(count.begin() + 1, count.end(), 0);
    while (count[0] < 1) {
      auto largest = std::max_element(count.begin() + 1, count.end());
      if (*largest <= 1) break;
      --*largest;
      ++count[0];
    }
    int s = 0;
    for (int i = 0; i < nsr && s < n_streams; ++i)
      for (int c = 0; c < count[static_cast<std::size_t>(i)] && s < n_streams; ++c) owner[static_cast<std::size_t>(s++)] = i;
  }

  double dmax = settings_.dmax;
  std::string reason = "maximum iterations";
  for (long it = 0; it < iterations && !counter.should_stop(); ++it) {
    // Streams flow to their river; a stream better than its river swaps with it.
    std::vector<Point> moved = streams;
    for (int s = 0; s < n_streams; ++s) {
      const Point& target = rivers[static_cast<std::size_t>(owner[static_cast<std::size_t>(s)])];
      for (std::size_t j = 0; j < n; ++j)
        moved[static_cast<std::size_t>(s)][j] += rng.uniform() * settings_.c * (target[j] - moved[static_cast<std::size_t>(s)][j]);
      clip(moved[static_cast<std::size_t>(s)], bounds);
    }
    std::vector<double> moved_cost = counter.evaluate(moved);
    streams = moved;
    stream_cost = moved_cost;
    for (int s = 0; s < n_streams; ++s) {
      int r = owner[static_cast<std::size_t>(s)];
      if (stream_cost[static_cast<std::size_t>(s)] < river_cost[static_cast<std::size_t>(r)]) {
        std::swap(streams[static_cast<std::size_t>(s)], rivers[static_cast<std::size_t>(r)]);
        std::swap(stream_cost[static_cast<std::size_t>(s)], river_cost[static_cast<std::size_t>(r)]);
      }
    }
    // Rivers flow to the sea; a river better than the sea becomes the sea.
    std::vector<Point> moved_rivers(rivers.begin() + 1, rivers.end());
    for (Point& river : moved_rivers) {
      for (std::size_t j = 0; j < n; ++j) river[j] += rng.uniform() * settings_.c * (rivers[0][j] - river[j]);
      clip(river, bounds);
    }
    std::vector<double> moved_river_cost = counter.evaluate(moved_rivers);
    for (int r = 1; r < nsr; ++r) {
      rivers[static_cast<std::size_t>(r)] = moved_rivers[static_cast<std::size_t>(r - 1)];
      river_cost[static_cast<std::size_t>(r)] = moved_river_cost[static_cast<std::size_t>(r - 1)];
      if (river_cost[static_cast<std::size_t>(r)] < river_cost[0]) {
        std::swap(rivers[static_cast<std::size_t>(r)], rivers[0]);
        std::swap(river_cost[static_cast<std::size_t>(r)], river_cost[0]);
      }
    }
    // Evaporation and raining: a river that reached the sea (or by chance,
    // probability 0.1) restarts at a random position with new streams; the
    // sea's streams that reached it rain down close to the sea.
    std::vector<Point> rained;
    std::vector<std::pair<int, int>> where;  // (kind 0 river / 1 stream, index)
    for (int r = 1; r < nsr; ++r) {
      if (distance(rivers[0], rivers[static_cast<std::size_t>(r)]) < dmax || rng.uniform() < 0.1) {
        rained.push_back(random_point(bounds, rng));
        where.push_back({0, r});
        for (int s = 0; s < n_streams; ++s)
          if (owner[static_cast<std::size_t>(s)] == r) {
            rained.push_back(random_point(bounds, rng));
            where.push_back({1, s});
          }
      }
    }
    for (int s = 0; s < n_streams; ++s) {
      if (owner[static_cast<std::size_t>(s)] == 0 && distance(rivers[0], streams[static_cast<std::size_t>(s)]) < dmax) {
        Point x = rivers[0];
        for (std::size_t j = 0; j < n; ++j) x[j] += std::sqrt(0.1) * rng.normal(0.0, 1.0) * (bounds.high[j] - bounds.low[j]);
        clip(x, bounds);
        rained.push_back(x);
        where.push_back({1, s});
      }
    }
    if (!rained.empty()) {
      std::vector<double> rained_cost = counter.evaluate(rained);
      for (std::size_t k = 0; k < rained.size(); ++k) {
        auto [kind, index] = where[k];
        if (kind == 0) {
          rivers[static_cast<std::size_t>(index)] = rained[k];
          river_cost[static_cast<std::size_t>(index)] = rained_cost[k];
        } else {
          streams[static_cast<std::size_t>(index)] = rained[k];
          stream_cost[static_cast<std::size_t>(index)] = rained_cost[k];
        }
      }
    }
    dmax -= dmax / static_cast<double>(iterations);
  }
  return counter.finish(budget_stop_reason(counter, reason));
}

}  // namespace demcal::inverse
