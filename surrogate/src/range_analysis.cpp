#include "demcal/surrogate/range_analysis.hpp"

#include <algorithm>
#include <numeric>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/data_columns.hpp"

namespace demcal::surrogate {

RangeAnalysis range_analysis(const std::vector<std::string>& factor_names, const Eigen::MatrixXd& factors,
                             const Eigen::VectorXd& y, const std::string& response) {
  RangeAnalysis result;
  result.response = response;
  result.runs = static_cast<int>(y.size());
  result.grand_mean = y.size() > 0 ? y.mean() : 0.0;
  for (std::size_t j = 0; j < factor_names.size(); ++j) {
    Eigen::VectorXd column = factors.col(static_cast<Eigen::Index>(j));
    std::vector<double> levels = distinct_values(column);
    if (levels.size() < 2)
      throw Error("range analysis: factor " + factor_names[j] + " has a single level; it cannot have an effect");
    if (2 * levels.size() > static_cast<std::size_t>(y.size()))
      throw Error("range analysis: factor " + factor_names[j] + " has " + std::to_string(levels.size()) +
                  " distinct values in " + std::to_string(y.size()) + " runs; it is not a design column with repeated levels");
    FactorRange factor;
    factor.factor = factor_names[j];
    for (double level : levels) {
      LevelSummary s;
      s.level = level;
      for (Eigen::Index i = 0; i < column.size(); ++i)
        if (column(i) == level) {
          ++s.count;
          s.sum += y(i);
        }
      s.mean = s.sum / s.count;
      factor.levels.push_back(s);
    }
    auto [lo, hi] = std::minmax_element(factor.levels.begin(), factor.levels.end(),
                                        [](const LevelSummary& a, const LevelSummary& b) { return a.mean < b.mean; });
    factor.range = hi->mean - lo->mean;
    factor.best_level = hi->level;
    result.factors.push_back(factor);
  }
  std::vector<std::size_t> order(result.factors.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return result.factors[a].range > result.factors[b].range;
  });
  for (std::size_t r = 0; r < order.size(); ++r) result.factors[order[r]].rank = static_cast<int>(r) + 1;
  return result;
}

}  // namespace demcal::surrogate
