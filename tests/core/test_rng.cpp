#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "demcal/core/rng.hpp"

using demcal::Rng;

TEST(Rng, SameSeedSameNumbersOtherSeedOrStreamOthers) {
  Rng a(123), b(123), c(124), d(123, 1);
  int same_c = 0, same_d = 0;
  for (int i = 0; i < 1000; ++i) {
    auto x = a();
    EXPECT_EQ(x, b());
    same_c += x == c();
    same_d += x == d();
  }
  EXPECT_EQ(same_c, 0);
  EXPECT_EQ(same_d, 0);
}

// The engine is seeded at the first draw (a bond with no strength scatter
// never draws): the numbers are still those of the seed sequence the class
// documents, whether the Rng was copied before its first draw or after.
TEST(Rng, SeedingAtTheFirstDrawKeepsTheDocumentedSequence) {
  const std::uint64_t seed = 0x0123456789abcdefull, stream = 0x626f6e64;
  std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                         static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(stream >> 32), 0x64656d63u};
  std::mt19937_64 reference(sequence);
  Rng fresh(seed, stream);
  Rng copied_unseeded = fresh;
  for (int i = 0; i < 5; ++i) EXPECT_EQ(fresh(), reference());
  Rng copied_seeded = fresh;
  for (int i = 0; i < 5; ++i) {
    const auto expected = reference();
    EXPECT_EQ(fresh(), expected);
    EXPECT_EQ(copied_seeded(), expected);
  }
  std::mt19937_64 again(sequence);
  EXPECT_EQ(copied_unseeded(), again());
}

TEST(Rng, UniformMeanAndRange) {
  Rng rng(5);
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  // standard error of the mean is 1/sqrt(12 n) = 6.5e-4; 5 sigma
  EXPECT_NEAR(sum / n, 0.5, 5 * 6.5e-4);
}

TEST(Rng, NormalMomentsWithinFiveStandardErrors) {
  Rng rng(9);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    double x = rng.normal(3.0, 2.0);
    sum += x;
    sum2 += x * x;
  }
  double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 3.0, 5 * 2.0 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(var), 2.0, 5 * 2.0 / std::sqrt(2.0 * n));
}

TEST(Rng, BelowIsUnbiasedAndShuffleIsAPermutation) {
  Rng rng(11);
  std::vector<int> counts(7, 0);
  const int n = 70000;
  for (int i = 0; i < n; ++i) ++counts[rng.below(7)];
  for (int c : counts) EXPECT_NEAR(c, n / 7.0, 5 * std::sqrt(n / 7.0));
  std::vector<int> v(50);
  std::iota(v.begin(), v.end(), 0);
  rng.shuffle(v);
  std::vector<int> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 50; ++i) EXPECT_EQ(sorted[i], i);
  EXPECT_FALSE(std::is_sorted(v.begin(), v.end()));
}
