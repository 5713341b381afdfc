#include "demcal/inverse/mean_shift.hpp"

#include <algorithm>
#include <numeric>

#include "demcal/core/error.hpp"

namespace demcal::inverse {

namespace {

std::vector<double> distances_from(const Eigen::MatrixXd& points, const Eigen::RowVectorXd& x) {
  std::vector<double> d(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) d[static_cast<std::size_t>(i)] = (points.row(i) - x).norm();
  return d;
}

}  // namespace

double estimate_bandwidth(const Eigen::MatrixXd& points, double quantile) {
  const Eigen::Index n = points.rows();
  if (n == 0) throw Error("mean-shift: no points to cluster");
  if (n == 1) return 0.0;
  const std::size_t k = std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(n) * quantile));
  double total = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    std::vector<double> d = distances_from(points, points.row(i));
    std::nth_element(d.begin(), d.begin() + static_cast<long>(k - 1), d.end());
    total += d[k - 1];
  }
  double bandwidth = total / static_cast<double>(n);
  if (bandwidth > 0) return bandwidth;
  // Tiny sets: k = 1 is the point itself. Use the median distance to the others.
  std::vector<double> all;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j) all.push_back((points.row(i) - points.row(j)).norm());
  std::nth_element(all.begin(), all.begin() + static_cast<long>(all.size() / 2), all.end());
  return all[all.size() / 2];
}

Clusters mean_shift(const Eigen::MatrixXd& points, double bandwidth, int max_iterations) {
  const Eigen::Index n = points.rows();
  if (n == 0) throw Error("mean-shift: no points to cluster");
  Clusters result;
  result.bandwidth = bandwidth > 0 ? bandwidth : estimate_bandwidth(points);
  if (!(result.bandwidth > 0)) {
    // Every point is the same: one cluster.
    result.centres = points.topRows(1);
    result.sizes = {static_cast<int>(n)};
    result.labels.assign(static_cast<std::size_t>(n), 0);
    return result;
  }
  const double h = result.bandwidth;
  std::vector<std::pair<Eigen::RowVectorXd, int>> converged;
  for (Eigen::Index s = 0; s < n; ++s) {
    Eigen::RowVectorXd centre = points.row(s);
    int within = 0;
    for (int it = 0; it < max_iterations; ++it) {
      Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(points.cols());
      within = 0;
      for (Eigen::Index i = 0; i < n; ++i)
        if ((points.row(i) - centre).norm() <= h) {
          sum += points.row(i);
          ++within;
        }
      if (within == 0) break;
      Eigen::RowVectorXd next = sum / within;
      bool done = (next - centre).norm() <= 1e-3 * h;
      centre = next;
      if (done) break;
    }
    if (within > 0) converged.push_back({centre, within});
  }
  // Strongest centres first; a centre within the bandwidth of a kept one is merged into it.
  std::stable_sort(converged.begin(), converged.end(), [](const auto& a, const auto& b) {
    if (a.second != b.second) return a.second > b.second;
    for (Eigen::Index j = 0; j < a.first.size(); ++j)
      if (a.first(j) != b.first(j)) return a.first(j) > b.first(j);
    return false;
  });
  std::vector<Eigen::RowVectorXd> kept;
  for (const auto& [centre, count] : converged) {
    bool near = false;
    for (const Eigen::RowVectorXd& k : kept) near = near || (k - centre).norm() < h;
    if (!near) kept.push_back(centre);
  }
  result.centres.resize(static_cast<Eigen::Index>(kept.size()), points.cols());
  for (std::size_t c = 0; c < kept.size(); ++c) result.centres.row(static_cast<Eigen::Index>(c)) = kept[c];
  result.sizes.assign(kept.size(), 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    std::vector<double> d = distances_from(result.centres, points.row(i));
    int label = static_cast<int>(std::min_element(d.begin(), d.end()) - d.begin());
    result.labels.push_back(label);
    ++result.sizes[static_cast<std::size_t>(label)];
  }
  // Order clusters by size (largest first), relabelling the points.
  std::vector<int> order(kept.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return result.sizes[static_cast<std::size_t>(a)] > result.sizes[static_cast<std::size_t>(b)]; });
  Clusters sorted = result;
  std::vector<int> new_label(kept.size());
  for (std::size_t c = 0; c < order.size(); ++c) {
    sorted.centres.row(static_cast<Eigen::Index>(c)) = result.centres.row(order[c]);
    sorted.sizes[c] = result.sizes[static_cast<std::size_t>(order[c])];
    new_label[static_cast<std::size_t>(order[c])] = static_cast<int>(c);
  }
  for (int& l : sorted.labels) l = new_label[static_cast<std::size_t>(l)];
  return sorted;
}

}  // namespace demcal::inverse
