// Mean-shift clustering and its bandwidth estimate against scikit-learn's
// documented examples, three separated blobs, and the tiny-set guards.
#include <gtest/gtest.h>

#include "demcal/core/rng.hpp"
#include "demcal/inverse/mean_shift.hpp"

namespace {

using namespace demcal;
using namespace demcal::inverse;

Eigen::MatrixXd sklearn_example() {
  Eigen::MatrixXd X(6, 2);
  X << 1, 1, 2, 1, 1, 0, 4, 7, 3, 5, 3, 6;
  return X;
}

TEST(MeanShift, BandwidthEstimateAsScikitLearn) {
  // sklearn.cluster.estimate_bandwidth(X, quantile=0.5) documents 1.61...
  EXPECT_NEAR(estimate_bandwidth(sklearn_example(), 0.5), 1.6191294403531442, 1e-12);
}

TEST(MeanShift, ScikitLearnDocumentedExample) {
  // MeanShift(bandwidth=2).fit(X): centres [[3.33, 6.0], [1.33, 0.67]], labels [1,1,1,0,0,0].
  Clusters c = mean_shift(sklearn_example(), 2.0);
  ASSERT_EQ(c.centres.rows(), 2);
  EXPECT_EQ(c.sizes, (std::vector<int>{3, 3}));
  Eigen::RowVectorXd a = c.centres.row(0), b = c.centres.row(1);
  if (a(0) < b(0)) std::swap(a, b);
  EXPECT_NEAR(a(0), 10.0 / 3, 1e-12);
  EXPECT_NEAR(a(1), 6.0, 1e-12);
  EXPECT_NEAR(b(0), 4.0 / 3, 1e-12);
  EXPECT_NEAR(b(1), 2.0 / 3, 1e-12);
  EXPECT_EQ(c.labels[0], c.labels[1]);
  EXPECT_EQ(c.labels[3], c.labels[5]);
  EXPECT_NE(c.labels[0], c.labels[3]);
}

TEST(MeanShift, RecoversThreeSeparatedGaussianBlobs) {
  Rng rng(4);
  const double centres[3][2] = {{0.2, 0.2}, {0.8, 0.3}, {0.5, 0.85}};
  Eigen::MatrixXd X(300, 2);
  for (int i = 0; i < 300; ++i)
    for (int j = 0; j < 2; ++j) X(i, j) = rng.normal(centres[i % 3][j], 0.03);
  Clusters c = mean_shift(X);  // estimated bandwidth
  ASSERT_EQ(c.centres.rows(), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(c.sizes[static_cast<std::size_t>(k)], 100);
    double best = 1e9;
    for (int m = 0; m < 3; ++m)
      best = std::min(best, std::hypot(c.centres(k, 0) - centres[m][0], c.centres(k, 1) - centres[m][1]));
    EXPECT_LT(best, 0.01);
  }
  // Each blob's points share one label.
  for (int i = 3; i < 300; ++i) EXPECT_EQ(c.labels[static_cast<std::size_t>(i)], c.labels[static_cast<std::size_t>(i % 3)]);
}

TEST(MeanShift, TinySetsDoNotGiveAZeroBandwidth) {
  // With the default quantile 0.3, six points give k = 1 (the point itself) and
  // scikit-learn's estimate is 0; the guard falls back to the median distance.
  EXPECT_GT(estimate_bandwidth(sklearn_example(), 0.3), 0.0);
  Eigen::MatrixXd same(4, 2);
  same.setConstant(0.5);
  Clusters c = mean_shift(same);
  EXPECT_EQ(c.centres.rows(), 1);
  EXPECT_EQ(c.sizes[0], 4);
  Eigen::MatrixXd one(1, 3);
  one << 0.1, 0.2, 0.3;
  EXPECT_EQ(mean_shift(one).centres.rows(), 1);
}

}  // namespace
