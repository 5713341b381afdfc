// Sensitivity indices against closed forms: Sobol indices of the Ishigami
// function (a = 7, b = 0.1 on [-pi, pi]^3) and Morris effects of a linear model.
#include <gtest/gtest.h>

#include <cmath>

#include "demcal/surrogate/sensitivity.hpp"

namespace {

using namespace demcal;

class Ishigami : public BoxModel {
 public:
  Ishigami() : BoxModel({{"x1", -M_PI, M_PI}, {"x2", -M_PI, M_PI}, {"x3", -M_PI, M_PI}}, {"f"}) {}
  void predict(const double* x, double* y) const override {
    y[0] = std::sin(x[0]) + 7.0 * std::pow(std::sin(x[1]), 2) + 0.1 * std::pow(x[2], 4) * std::sin(x[0]);
  }
};

class Linear : public BoxModel {
 public:
  Linear() : BoxModel({{"a", 0, 2}, {"b", 10, 30}}, {"y"}) {}
  void predict(const double* x, double* y) const override { y[0] = 3.0 * x[0] - 0.5 * x[1]; }
};

TEST(Sensitivity, SobolIndicesOfTheIshigamiFunction) {
  Ishigami model;
  auto indices = surrogate::sobol_indices(model, 1 << 14, 1);
  ASSERT_EQ(indices.size(), 1u);
  const auto& s = indices[0];
  EXPECT_NEAR(s.variance, 13.844588, 0.25);
  // Exact: S1 = 0.3139, 0.4424, 0; ST = 0.5576, 0.4424, 0.2437. Estimator error at N = 16384 is < 0.01.
  EXPECT_NEAR(s.first[0], 0.3139, 0.02);
  EXPECT_NEAR(s.first[1], 0.4424, 0.02);
  EXPECT_NEAR(s.first[2], 0.0, 0.02);
  EXPECT_NEAR(s.total[0], 0.5576, 0.02);
  EXPECT_NEAR(s.total[1], 0.4424, 0.02);
  EXPECT_NEAR(s.total[2], 0.2437, 0.02);
  EXPECT_EQ(s.evaluations, (1 << 14) * 5);
  for (double c : s.first_conf) EXPECT_LT(c, 0.05);
}

TEST(Sensitivity, MorrisEffectsOfALinearModelAreItsSlopesTimesTheRange) {
  Linear model;
  auto indices = surrogate::morris_indices(model, 20, 3);
  const auto& m = indices[0];
  EXPECT_NEAR(m.mu[0], 3.0 * 2.0, 1e-9);
  EXPECT_NEAR(m.mu_star[0], 6.0, 1e-9);
  EXPECT_NEAR(m.mu[1], -0.5 * 20.0, 1e-9);
  EXPECT_NEAR(m.mu_star[1], 10.0, 1e-9);
  EXPECT_NEAR(m.sigma[0], 0.0, 1e-9);  // no interactions, no curvature
  EXPECT_EQ(m.evaluations, 20 * 3);
}

TEST(Sensitivity, SameSeedSameIndices) {
  Ishigami model;
  auto a = surrogate::sobol_indices(model, 256, 7);
  auto b = surrogate::sobol_indices(model, 256, 7);
  EXPECT_EQ(a[0].first, b[0].first);
  EXPECT_EQ(a[0].total_conf, b[0].total_conf);
}

}  // namespace
