#pragma once
// What a design is, measured rather than assumed: level counts per column,
// orthogonality of main effects (strength 2 or proportional frequencies),
// duplicated runs, distances and correlations.
#include <string>
#include <utility>
#include <vector>

#include "demcal/doe/design.hpp"

namespace demcal::doe {

struct ColumnLevels {
  std::vector<double> values;  // distinct coded values, increasing (empty: continuous)
  std::vector<int> counts;     // runs at each value
};

struct DesignProperties {
  std::size_t runs = 0;
  std::size_t columns = 0;
  std::vector<ColumnLevels> levels;  // per column
  bool discrete = false;             // every column has at most 12 distinct values
  bool strength_two = false;         // every pair: all level combinations equally often
  bool proportional_frequencies = false;  // every pair: n_ab N = n_a n_b
  std::vector<std::pair<int, int>> non_proportional_pairs;
  int duplicate_runs = 0;            // rows equal to an earlier row
  double min_distance = 0;           // on columns scaled to [0, 1]
  double phi_p = 0;                  // p = 10, same scaling
  double max_abs_correlation = 0;
  std::pair<int, int> max_correlation_pair{-1, -1};
};

DesignProperties analyse(const Design& design);
std::string properties_markdown(const Design& design, const DesignProperties& properties);

}  // namespace demcal::doe
