#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "demcal/core/error.hpp"
#include "demcal/doe/space_filling.hpp"

using namespace demcal::doe;

namespace {

// Each column has exactly one point in each of the n strata [k/n, (k+1)/n).
void expect_latin(const Eigen::MatrixXd& x) {
  const Eigen::Index n = x.rows();
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    std::set<long> strata;
    for (Eigen::Index i = 0; i < n; ++i) {
      ASSERT_GE(x(i, j), 0.0);
      ASSERT_LT(x(i, j), 1.0);
      strata.insert(static_cast<long>(std::floor(x(i, j) * n)));
    }
    EXPECT_EQ(static_cast<Eigen::Index>(strata.size()), n) << "column " << j;
  }
}

LhsOptions options(int runs, int factors, LhsCriterion criterion, std::uint64_t seed) {
  LhsOptions o;
  o.runs = runs;
  o.factors = factors;
  o.criterion = criterion;
  o.seed = seed;
  return o;
}

}  // namespace

TEST(LatinHypercube, OnePointPerStratumForEveryCriterion) {
  for (LhsCriterion c : {LhsCriterion::Random, LhsCriterion::Center, LhsCriterion::Maximin, LhsCriterion::PhiP})
    expect_latin(latin_hypercube(options(17, 4, c, 3)).coded);
  Design centred = latin_hypercube(options(10, 2, LhsCriterion::Center, 1));
  for (Eigen::Index i = 0; i < 10; ++i) EXPECT_NEAR(std::fmod(centred.coded(i, 0) * 10, 1.0), 0.5, 1e-12);
}

TEST(LatinHypercube, SameSeedSameDesignOtherSeedAnother) {
  for (LhsCriterion c : {LhsCriterion::Random, LhsCriterion::PhiP}) {
    Design a = latin_hypercube(options(12, 3, c, 42));
    Design b = latin_hypercube(options(12, 3, c, 42));
    Design other = latin_hypercube(options(12, 3, c, 43));
    EXPECT_TRUE(a.coded == b.coded);
    EXPECT_FALSE(a.coded == other.coded);
  }
}

TEST(LatinHypercube, OptimisedPhiPBeatsTheBestOfOneHundredRandomOnes) {
  const int runs = 20, factors = 3;
  double best_random_phi = INFINITY, best_random_distance = 0;
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    Eigen::MatrixXd x = latin_hypercube(options(runs, factors, LhsCriterion::Random, seed)).coded;
    best_random_phi = std::min(best_random_phi, phi_p(x, 10.0));
    best_random_distance = std::max(best_random_distance, min_distance(x));
  }
  Eigen::MatrixXd optimised = latin_hypercube(options(runs, factors, LhsCriterion::PhiP, 7)).coded;
  EXPECT_LT(phi_p(optimised, 10.0), best_random_phi);
  Eigen::MatrixXd maximin = latin_hypercube(options(runs, factors, LhsCriterion::Maximin, 7)).coded;
  EXPECT_GT(min_distance(maximin), best_random_distance);
}

TEST(LatinHypercube, BadInputIsRejected) {
  EXPECT_THROW(latin_hypercube(options(1, 2, LhsCriterion::Random, 1)), demcal::Error);
  EXPECT_THROW(latin_hypercube(options(5, 0, LhsCriterion::Random, 1)), demcal::Error);
  EXPECT_THROW(parse_lhs_criterion("best"), demcal::Error);
}

TEST(Sobol, ScrambledPointsStayANet) {
  // 2^m scrambled Sobol points: every 1-D projection has one point per
  // interval of width 2^-m, and the first two dimensions a (0, m, 2)-net: one
  // point in every 2^-a x 2^-(m-a) box.
  const int m = 6, n = 1 << m;
  Design d = sobol(n, 5, 11);
  expect_latin(d.coded);
  for (int a = 0; a <= m; ++a) {
    std::set<std::pair<long, long>> boxes;
    for (int i = 0; i < n; ++i)
      boxes.insert({static_cast<long>(std::floor(d.coded(i, 0) * (1 << a))),
                    static_cast<long>(std::floor(d.coded(i, 1) * (1 << (m - a))))});
    EXPECT_EQ(static_cast<int>(boxes.size()), n) << "a = " << a;
  }
}

TEST(Sobol, SeededAndDistinctFromAnotherSeed) {
  EXPECT_TRUE(sobol(16, 3, 5).coded == sobol(16, 3, 5).coded);
  EXPECT_FALSE(sobol(16, 3, 5).coded == sobol(16, 3, 6).coded);
  EXPECT_THROW(sobol(1, 3, 5), demcal::Error);
}

TEST(Distances, PhiPAndMinDistanceOnAKnownDesign) {
  Eigen::MatrixXd x(3, 2);
  x << 0, 0, 3, 4, 0, 1;  // distances 5, 1, sqrt(18)
  EXPECT_NEAR(min_distance(x), 1.0, 1e-15);
  double expected = std::pow(std::pow(5.0, -2) + 1.0 + std::pow(18.0, -1.0), 0.5);
  EXPECT_NEAR(phi_p(x, 2.0), expected, 1e-15);
}
