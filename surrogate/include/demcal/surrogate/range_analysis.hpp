#pragma once
// Range (extreme-difference) analysis of an orthogonal design: for every
// factor the sum K_i and mean k_i of the response at each level, the range
// R = max k - min k, and the factors ranked by R (1 = largest effect).
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace demcal::surrogate {

struct LevelSummary {
  double level = 0.0;   // the column's value at this level
  int count = 0;        // runs at this level
  double sum = 0.0;     // K_i
  double mean = 0.0;    // k_i = K_i / count
};

struct FactorRange {
  std::string factor;
  std::vector<LevelSummary> levels;  // by increasing level value
  double range = 0.0;                // R
  int rank = 0;                      // 1 = largest R
  double best_level = 0.0;           // level with the largest mean
};

struct RangeAnalysis {
  std::string response;
  double grand_mean = 0.0;
  int runs = 0;
  std::vector<FactorRange> factors;  // in the order given
};

// `factors`: runs x factor columns (level values); `y`: the response.
// Throws when a factor has one level or no level repeated (not a design column).
RangeAnalysis range_analysis(const std::vector<std::string>& factor_names, const Eigen::MatrixXd& factors,
                             const Eigen::VectorXd& y, const std::string& response);

}  // namespace demcal::surrogate
