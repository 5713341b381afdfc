#include "demcal/inverse/tolerance_search.hpp"

#include <algorithm>
#include <cmath>

#include "demcal/doe/space_filling.hpp"
#include "demcal/inverse/mean_shift.hpp"

namespace demcal::inverse {

SearchRun tolerance_search(const InversionProblem& problem, const SearchSettings& settings, std::uint64_t seed,
                           const Budget& budget) {
  const Bounds& b = problem.bounds();
  const std::size_t n = b.size();
  doe::LhsOptions lhs;
  lhs.runs = settings.samples;
  lhs.factors = static_cast<int>(n);
  lhs.seed = seed;
  Eigen::MatrixXd unit = doe::latin_hypercube(lhs).coded;
  auto natural = [&](const Eigen::RowVectorXd& u) {
    Point x(n);
    for (std::size_t j = 0; j < n; ++j) x[j] = b.low[j] + u(static_cast<Eigen::Index>(j)) * (b.high[j] - b.low[j]);
    return x;
  };
  const std::vector<double> targets = problem.target_values();
  SearchRun out;
  // Predictions are needed per output (the tolerance is per target), so the
  // counter's objective keeps them for the filter.
  std::vector<std::vector<double>> predictions;
  EvaluationCounter counter(
      [&](const std::vector<Point>& points, std::vector<double>& values) {
        values.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
          predictions.push_back(problem.predict_targets(points[i]));
          values[i] = relative_objective(problem.objective_kind(), predictions.back(), targets);
        }
      },
      budget);
  std::vector<Point> samples;
  for (Eigen::Index i = 0; i < unit.rows(); ++i) samples.push_back(natural(unit.row(i)));
  counter.evaluate(samples);
  std::vector<Eigen::Index> kept_rows;
  for (std::size_t i = 0; i < predictions.size(); ++i)
    if (max_relative_error(predictions[i], targets) <= settings.tolerance) kept_rows.push_back(static_cast<Eigen::Index>(i));
  for (Eigen::Index r : kept_rows) out.kept.push_back(samples[static_cast<std::size_t>(r)]);
  if (!kept_rows.empty()) {
    Eigen::MatrixXd kept_unit(static_cast<Eigen::Index>(kept_rows.size()), static_cast<Eigen::Index>(n));
    for (std::size_t k = 0; k < kept_rows.size(); ++k) kept_unit.row(static_cast<Eigen::Index>(k)) = unit.row(kept_rows[k]);
    Clusters clusters = mean_shift(kept_unit);
    out.bandwidth = clusters.bandwidth;
    std::vector<Point> centres;
    for (Eigen::Index c = 0; c < clusters.centres.rows(); ++c) centres.push_back(natural(clusters.centres.row(c)));
    std::size_t first = predictions.size();
    counter.evaluate(centres);
    for (std::size_t c = 0; c < centres.size() && first + c < predictions.size(); ++c) {
      Candidate candidate;
      candidate.x = centres[c];
      candidate.size = clusters.sizes[c];
      candidate.predicted = predictions[first + c];
      candidate.objective = relative_objective(problem.objective_kind(), candidate.predicted, targets);
      candidate.max_relative_error = max_relative_error(candidate.predicted, targets);
      // A centre of a curved cluster can itself fall outside the tolerance: say so.
      candidate.within_tolerance = candidate.max_relative_error <= settings.tolerance;
      out.candidates.push_back(candidate);
    }
  }
  out.run = counter.finish(kept_rows.empty() ? "no sampled point within the tolerance"
                                             : std::to_string(kept_rows.size()) + " points within the tolerance");
  return out;
}

}  // namespace demcal::inverse
