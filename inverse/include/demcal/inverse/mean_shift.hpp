#pragma once
// Mean-shift clustering with a flat kernel, as scikit-learn's MeanShift does
// it (every point a seed, shift to the mean of the points within the
// bandwidth, merge centres closer than the bandwidth, strongest first), and
// its bandwidth estimate (mean distance to the k-th nearest neighbour, the
// point itself included, k = int(n * quantile)).
#include <vector>

#include <Eigen/Dense>

namespace demcal::inverse {

// Rows are points. A set so small that the estimate is 0 (k = 1 counts only
// the point itself) falls back to the median distance to the other points;
// identical points give 0.
double estimate_bandwidth(const Eigen::MatrixXd& points, double quantile = 0.3);

struct Clusters {
  Eigen::MatrixXd centres;   // one row per cluster, largest first
  std::vector<int> sizes;    // points labelled with each centre
  std::vector<int> labels;   // nearest centre of each point
  double bandwidth = 0.0;
};

// bandwidth <= 0: estimated. Identical points (bandwidth 0) form one cluster.
Clusters mean_shift(const Eigen::MatrixXd& points, double bandwidth = 0.0, int max_iterations = 300);

}  // namespace demcal::inverse
