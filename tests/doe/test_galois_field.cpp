#include <gtest/gtest.h>

#include "demcal/core/error.hpp"
#include "demcal/doe/galois_field.hpp"

using demcal::doe::GaloisField;

class FieldAxioms : public ::testing::TestWithParam<int> {};

TEST_P(FieldAxioms, HoldForEveryElement) {
  GaloisField f(GetParam());
  int q = f.order();
  for (int a = 0; a < q; ++a) {
    EXPECT_EQ(f.add(a, 0), a);
    EXPECT_EQ(f.mul(a, 1), a);
    EXPECT_EQ(f.add(a, f.neg(a)), 0);
    if (a) {
      EXPECT_EQ(f.mul(a, f.inv(a)), 1);
    }
    for (int b = 0; b < q; ++b) {
      EXPECT_EQ(f.add(a, b), f.add(b, a));
      EXPECT_EQ(f.mul(a, b), f.mul(b, a));
      if (a && b) {
        EXPECT_NE(f.mul(a, b), 0) << "zero divisor in GF(" << q << ")";
      }
      for (int c = 0; c < q; c += (q > 9 ? 3 : 1)) {
        EXPECT_EQ(f.mul(a, f.add(b, c)), f.add(f.mul(a, b), f.mul(a, c)));
        EXPECT_EQ(f.mul(a, f.mul(b, c)), f.mul(f.mul(a, b), c));
        EXPECT_EQ(f.add(a, f.add(b, c)), f.add(f.add(a, b), c));
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(PrimePowers, FieldAxioms, ::testing::Values(2, 3, 4, 5, 7, 8, 9, 16, 25, 27));

TEST(GaloisField, Gf4MultiplicationTable) {
  // GF(4) = {0, 1, a, a+1} modulo x^2 + x + 1 (a = 2, a+1 = 3).
  GaloisField f(4);
  int expected[4][4] = {{0, 0, 0, 0}, {0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      EXPECT_EQ(f.mul(a, b), expected[a][b]);
      EXPECT_EQ(f.add(a, b), a ^ b);
    }
}

TEST(GaloisField, RejectsOrdersThatAreNotPrimePowers) {
  for (int q : {0, 1, 6, 10, 12, 18})
    EXPECT_THROW(GaloisField f(q), demcal::Error) << q;
  EXPECT_EQ(GaloisField::prime_power(64), std::make_pair(2, 6));
  EXPECT_EQ(GaloisField::prime_power(81), std::make_pair(3, 4));
}
