#include <gtest/gtest.h>

#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/doe/properties.hpp"
#include "demcal/doe/response_surface.hpp"

using namespace demcal::doe;

TEST(CentralComposite, MinitabDefaultForTwoFactors) {
  Design d = central_composite({});
  ASSERT_EQ(d.runs(), 13u);  // 4 cube + 4 axial + 5 centre
  EXPECT_NEAR(std::stod(d.settings.at("alpha")), std::sqrt(2.0), 1e-12);
  int centre = 0;
  for (std::size_t i = 0; i < d.runs(); ++i) centre += d.coded.row(i).norm() == 0;
  EXPECT_EQ(centre, 5);
  EXPECT_NEAR(d.coded.cwiseAbs().maxCoeff(), 1.41421356, 1e-8);
}

TEST(CentralComposite, RotatableAlphaMakesSecondMomentsIsotropic) {
  for (int k = 2; k <= 6; ++k) {
    CcdOptions options;
    options.factors = k;
    Design d = central_composite(options);
    EXPECT_NEAR(std::stod(d.settings.at("alpha")), std::pow(2.0, k / 4.0), 1e-12);
    // Rotatable: sum x_i^4 = 3 sum x_i^2 x_j^2, and odd moments vanish.
    double pure = (d.coded.col(0).array().pow(4)).sum();
    double mixed = (d.coded.col(0).array().square() * d.coded.col(1).array().square()).sum();
    EXPECT_NEAR(pure, 3 * mixed, 1e-9) << k;
    EXPECT_NEAR((d.coded.col(0).array() * d.coded.col(1).array()).sum(), 0.0, 1e-12);
    EXPECT_EQ(static_cast<int>(d.runs()), (1 << k) + 2 * k + ccd_default_center(k));
  }
}

TEST(CentralComposite, OrthogonalFaceAndInscribed) {
  // Orthogonal quadratic alpha for k = 2 with 5 centre points: 1.2671.
  EXPECT_NEAR(ccd_alpha("orthogonal", 2, 5), 1.2671, 1e-4);
  CcdOptions options;
  options.factors = 3;
  options.alpha = "orthogonal";
  Design orth = central_composite(options);
  // Orthogonal: the centred square columns are uncorrelated.
  Eigen::ArrayXd a = orth.coded.col(0).array().square(), b = orth.coded.col(1).array().square();
  EXPECT_NEAR(((a - a.mean()) * (b - b.mean())).sum(), 0.0, 1e-9);

  options.alpha = "rotatable";
  options.type = "faced";
  Design faced = central_composite(options);
  EXPECT_EQ(faced.coded.cwiseAbs().maxCoeff(), 1.0);
  options.type = "inscribed";
  Design inscribed = central_composite(options);
  EXPECT_NEAR(inscribed.coded.cwiseAbs().maxCoeff(), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(inscribed.coded(0, 0)), 1.0 / std::pow(8.0, 0.25), 1e-15);
  options.type = "circumscribed";
  options.alpha = "1.5";
  options.center = 2;
  Design number = central_composite(options);
  EXPECT_EQ(number.runs(), 8u + 6u + 2u);
  EXPECT_NEAR(number.coded.cwiseAbs().maxCoeff(), 1.5, 1e-15);
}

TEST(CentralComposite, BadInputIsRejected) {
  CcdOptions options;
  options.alpha = "0";
  EXPECT_THROW(central_composite(options), demcal::Error);
  options.alpha = "-1";
  EXPECT_THROW(central_composite(options), demcal::Error);
  options.alpha = "wide";
  EXPECT_THROW(central_composite(options), demcal::Error);
  options = {};
  options.factors = 1;
  EXPECT_THROW(central_composite(options), demcal::Error);
  options = {};
  options.type = "round";
  EXPECT_THROW(central_composite(options), demcal::Error);
}

TEST(BoxBehnken, MinitabRunCountsAndCentrePoints) {
  int expected_runs[] = {15, 27, 46, 54, 62};
  int expected_centre[] = {3, 3, 6, 6, 6};
  for (int k = 3; k <= 7; ++k) {
    Design d = box_behnken(k);
    EXPECT_EQ(static_cast<int>(d.runs()), expected_runs[k - 3]) << k;
    int centre = 0;
    int block_size = k <= 5 ? 2 : 3;
    for (std::size_t i = 0; i < d.runs(); ++i) {
      int nonzero = 0;
      for (int j = 0; j < k; ++j) {
        double v = d.coded(i, j);
        EXPECT_TRUE(v == 0 || v == 1 || v == -1);
        nonzero += v != 0;
      }
      // Each run is the centre or the mid-point of an edge (k <= 5) / of a
      // 3-dimensional face (k = 6, 7) of the cube.
      if (nonzero == 0) ++centre;
      else EXPECT_EQ(nonzero, block_size);
    }
    EXPECT_EQ(centre, expected_centre[k - 3]);
    // Every factor sits at -1, 0, +1 only and the columns are balanced.
    EXPECT_NEAR(d.coded.colwise().sum().cwiseAbs().maxCoeff(), 0.0, 1e-12);
  }
}

TEST(BoxBehnken, SevenFactorsFromTheFanoPlane) {
  // In the Fano plane every pair of factors shares exactly one block, so every
  // pair appears together in exactly 8 runs (one 2^3 block).
  Design d = box_behnken(7);
  for (int a = 0; a < 7; ++a)
    for (int b = a + 1; b < 7; ++b) {
      int together = 0;
      for (std::size_t i = 0; i < d.runs(); ++i) together += d.coded(i, a) != 0 && d.coded(i, b) != 0;
      EXPECT_EQ(together, 8) << a << "," << b;
    }
}

TEST(BoxBehnken, FactorCountOutsideThreeToSevenIsRejected) {
  EXPECT_THROW(box_behnken(2), demcal::Error);
  EXPECT_THROW(box_behnken(8), demcal::Error);
  EXPECT_EQ(box_behnken(3, 1).runs(), 13u);
}
