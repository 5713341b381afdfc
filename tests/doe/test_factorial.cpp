#include <gtest/gtest.h>

#include <set>

#include "demcal/core/error.hpp"
#include "demcal/doe/factorial.hpp"
#include "demcal/doe/properties.hpp"

using namespace demcal::doe;

TEST(FullFactorial, EveryCombinationOnceFirstColumnFastest) {
  Design d = full_factorial({2, 3, 2});
  ASSERT_EQ(d.runs(), 12u);
  std::set<std::vector<double>> rows;
  for (std::size_t i = 0; i < d.runs(); ++i) rows.insert({d.coded(i, 0), d.coded(i, 1), d.coded(i, 2)});
  EXPECT_EQ(rows.size(), 12u);
  EXPECT_EQ(d.coded(0, 0), -1);
  EXPECT_EQ(d.coded(1, 0), 1);   // first column changes fastest
  EXPECT_EQ(d.coded(2, 1), 0);   // three levels: -1, 0, +1
  EXPECT_TRUE(analyse(d).strength_two);
  EXPECT_THROW(full_factorial({2, 1}), demcal::Error);
}

TEST(Hadamard, OrthogonalRowsForEveryBuiltInOrder) {
  for (int n : {2, 4, 8, 12, 16, 20, 24, 32, 40, 48, 80}) {
    LevelMatrix h = hadamard(n);
    Eigen::MatrixXi product = h.transpose() * h;
    EXPECT_TRUE(product.isApprox(n * Eigen::MatrixXi::Identity(n, n))) << n;
  }
  EXPECT_THROW(hadamard(28), demcal::Error);
  EXPECT_THROW(hadamard(6), demcal::Error);
}

TEST(PlackettBurman, SmallestMultipleOfFourAboveTheFactorCount) {
  EXPECT_EQ(plackett_burman(3).runs(), 4u);
  EXPECT_EQ(plackett_burman(7).runs(), 8u);
  EXPECT_EQ(plackett_burman(8).runs(), 12u);
  EXPECT_EQ(plackett_burman(11).runs(), 12u);
  EXPECT_EQ(plackett_burman(19).runs(), 20u);
  EXPECT_EQ(plackett_burman(27).runs(), 32u);  // 28 is not built in
  Design d = plackett_burman(11);
  // Columns are balanced and mutually orthogonal.
  Eigen::MatrixXd gram = d.coded.transpose() * d.coded;
  EXPECT_TRUE(gram.isApprox(12.0 * Eigen::MatrixXd::Identity(11, 11)));
  EXPECT_NEAR(d.coded.colwise().sum().cwiseAbs().maxCoeff(), 0.0, 1e-12);
  EXPECT_THROW(plackett_burman(11, 28), demcal::Error);
  EXPECT_THROW(plackett_burman(12, 12), demcal::Error);
}

TEST(FractionalFactorial, GeneratorsDefineTheAddedColumns) {
  Design d = fractional_factorial(5, {"E=ABCD"}, 0);
  ASSERT_EQ(d.runs(), 16u);
  for (std::size_t i = 0; i < 16; ++i)
    EXPECT_EQ(d.coded(i, 4), d.coded(i, 0) * d.coded(i, 1) * d.coded(i, 2) * d.coded(i, 3));
  EXPECT_EQ(d.settings.at("resolution"), "V");
  Design negated = fractional_factorial(4, {"D=-ABC"}, 0);
  for (std::size_t i = 0; i < 8; ++i)
    EXPECT_EQ(negated.coded(i, 3), -negated.coded(i, 0) * negated.coded(i, 1) * negated.coded(i, 2));
  EXPECT_EQ(negated.settings.at("resolution"), "IV");
}

TEST(FractionalFactorial, ChosenGeneratorsReachTheKnownBestResolution) {
  // Textbook maximum resolutions (Box, Hunter & Hunter): 2^(5-1) V, 2^(6-2) IV,
  // 2^(7-3) IV, 2^(8-4) IV, 2^(7-4) III, 2^(6-1) VI.
  struct Case { int factors, runs; const char* resolution; };
  for (Case c : {Case{5, 16, "V"}, Case{6, 16, "IV"}, Case{7, 16, "IV"}, Case{8, 16, "IV"}, Case{7, 8, "III"},
                 Case{6, 32, "VI"}}) {
    Design d = fractional_factorial(c.factors, {}, c.runs);
    EXPECT_EQ(static_cast<int>(d.runs()), c.runs);
    EXPECT_EQ(d.settings.at("resolution"), c.resolution) << c.factors << " factors in " << c.runs << " runs";
    Eigen::MatrixXd gram = d.coded.transpose() * d.coded;
    EXPECT_TRUE(gram.isApprox(c.runs * Eigen::MatrixXd::Identity(c.factors, c.factors)));
  }
}

TEST(FractionalFactorial, BadGeneratorsAreRejected) {
  EXPECT_THROW(fractional_factorial(4, {"D=AE"}, 0), demcal::Error);   // E is not a base factor
  EXPECT_THROW(fractional_factorial(4, {"E=ABC"}, 0), demcal::Error);  // defines the wrong factor
  EXPECT_THROW(fractional_factorial(4, {"D=A"}, 0), demcal::Error);    // aliases D with A
  EXPECT_THROW(fractional_factorial(4, {"D=AAB"}, 0), demcal::Error);
  EXPECT_THROW(fractional_factorial(5, {}, 12), demcal::Error);        // not a power of two
  EXPECT_THROW(fractional_factorial(12, {}, 8), demcal::Error);        // 8 runs hold 7 factors
}
