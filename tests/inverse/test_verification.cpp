// The verification table against a hand computation.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/inverse/verification.hpp"

namespace {

using namespace demcal::inverse;

TEST(Verification, HandComputedTable) {
  // sigma_u over three seeds: 29, 30, 31 -> mean 30, SD 1, CV 3.333 %, error 0 against 30.
  // E: 27, 28, 29 -> mean 28, error -6.667 % against 30: fails a 5 % tolerance.
  std::vector<SeedRun> seeds = {{1, true, "", {{"sigma_u_MPa", 29}, {"E_GPa", 27}}},
                                {2, true, "", {{"sigma_u_MPa", 30}, {"E_GPa", 28}}},
                                {3, true, "", {{"sigma_u_MPa", 31}, {"E_GPa", 29}}},
                                {4, false, "unstable", {}}};
  Verification v = verify({{"sigma_u_MPa", 30}, {"E_GPa", 30}}, {{"sigma_u_MPa", 30.5}}, seeds, 0.05);
  ASSERT_EQ(v.rows.size(), 2u);
  const VerificationRow& e = v.rows[0];  // outputs in name order: E_GPa, sigma_u_MPa
  const VerificationRow& s = v.rows[1];
  EXPECT_EQ(s.output, "sigma_u_MPa");
  EXPECT_EQ(s.runs, 3);
  EXPECT_DOUBLE_EQ(s.mean, 30.0);
  EXPECT_DOUBLE_EQ(s.sd, 1.0);
  EXPECT_NEAR(s.cv_pct, 100.0 / 30.0, 1e-12);
  EXPECT_NEAR(s.relative_error_pct, 0.0, 1e-12);
  EXPECT_TRUE(s.passed);
  EXPECT_DOUBLE_EQ(s.predicted, 30.5);
  EXPECT_NEAR(e.relative_error_pct, -100.0 * 2.0 / 30.0, 1e-12);
  EXPECT_FALSE(e.passed);
  EXPECT_TRUE(std::isnan(e.predicted));
  EXPECT_FALSE(v.passed);
  // 95 % interval: t(0.975, 2) = 4.302652730 (tables), half-width 4.302652730 / sqrt(3) = 2.484138.
  EXPECT_NEAR(s.ci95_low, 30.0 - 2.484138, 1e-6);
  EXPECT_NEAR(s.ci95_high, 30.0 + 2.484138, 1e-6);
  EXPECT_NEAR(s.half_width_pct, 100.0 * 2.484138 / 30.0, 1e-5);
  EXPECT_EQ(s.verdict, kMeanInsideBand);  // the mean is inside 28.5..31.5, the interval is not
  EXPECT_EQ(e.verdict, kOutside);
  EXPECT_EQ(v.verdict, kOutside);
  std::string md = verification_markdown(v);
  EXPECT_NE(md.find("| sigma_u_MPa | 30 | 30.5 | 30 | 1 | 3.33 | 27.52 to 32.48 | 8.28 | 0.00 | yes | mean_inside_band |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("seed 4 failed: unstable"), std::string::npos) << md;
  EXPECT_EQ(verification_json(v)["outputs"]["E_GPa"]["passed"], false);
}

TEST(Verification, StudentTQuantilesMatchTables) {
  // Two-sided 95 % points of Student's t (e.g. NIST/SEMATECH e-Handbook, table 1.3.6.7.2).
  EXPECT_NEAR(student_t_975(1), 12.706, 5e-4);
  EXPECT_NEAR(student_t_975(4), 2.776, 5e-4);
  EXPECT_NEAR(student_t_975(19), 2.093, 5e-4);
  EXPECT_NEAR(student_t_975(100), 1.984, 5e-4);
  EXPECT_TRUE(std::isnan(student_t_975(0)));
}

TEST(Verification, IntervalInsideTheBand) {
  // 100 +- 1 over five seeds: half-width t(4) * sd / sqrt(5) = 2.776 * 1.5811 / 2.2361 = 1.963 < 5.
  std::vector<SeedRun> seeds;
  const double values[] = {99, 101, 98, 102, 100};
  for (int i = 0; i < 5; ++i) seeds.push_back({std::uint64_t(i + 1), true, "", {{"E_GPa", values[i]}}});
  Verification v = verify({{"E_GPa", 100}}, {}, seeds, 0.05);
  EXPECT_EQ(v.rows[0].verdict, kIntervalInsideBand);
  EXPECT_EQ(v.verdict, kIntervalInsideBand);
  EXPECT_NEAR(v.rows[0].half_width_pct, 2.776445 * std::sqrt(2.5) / std::sqrt(5.0), 1e-5);
  EXPECT_EQ(seeds_wanted(v, 20), 5);  // narrow enough already
}

TEST(Verification, SeedsWantedFromTheMeasuredSpread) {
  // CV 10 % at the target: t(n-1) 10 / sqrt(n) <= 5 first holds at n = 18
  // (t(16) 10 / sqrt(17) = 5.14, t(17) 10 / sqrt(18) = 4.97).
  std::vector<SeedRun> seeds;
  const double values[] = {90, 110, 90, 110, 100};  // sd 10 exactly: squares 100+100+100+100+0 over 4
  for (int i = 0; i < 5; ++i) seeds.push_back({std::uint64_t(i + 1), true, "", {{"sigma_u_MPa", values[i]}}});
  Verification v = verify({{"sigma_u_MPa", 100}}, {}, seeds, 0.05);
  ASSERT_DOUBLE_EQ(v.rows[0].sd, 10.0);
  EXPECT_EQ(seeds_wanted(v, 20), 18);
  EXPECT_EQ(seeds_wanted(v, 12), 12);  // capped
  EXPECT_EQ(seeds_wanted(v, 5), 5);    // nothing to add
  // One seed in six failed: the wanted runs are found for the seeds that give outputs.
  seeds.push_back({6, false, "burst", {}});
  Verification lossy = verify({{"sigma_u_MPa", 100}}, {}, seeds, 0.05);
  EXPECT_EQ(seeds_wanted(lossy, 30), 22);  // ceil(18 / (5/6)) = 22
}

TEST(Verification, NoSeedsAddedWhenTheIntervalIsOutsideTheBand) {
  // Mean 130 +- a little against 100: more seeds narrow the interval, they do not move it in.
  std::vector<SeedRun> seeds;
  const double values[] = {129, 131, 130};
  for (int i = 0; i < 3; ++i) seeds.push_back({std::uint64_t(i + 1), true, "", {{"E_GPa", values[i]}}});
  Verification v = verify({{"E_GPa", 100}}, {}, seeds, 0.001);
  EXPECT_TRUE(interval_outside_band(v));
  EXPECT_EQ(seeds_wanted(v, 20), 3);
  EXPECT_EQ(v.verdict, kOutside);
}

TEST(Verification, OneSeedCannotPass) {
  Verification v = verify({{"nu", 0.2}}, {}, {{1, true, "", {{"nu", 0.2}}}}, 0.05);
  EXPECT_FALSE(v.passed);  // no spread from a single run
  EXPECT_TRUE(std::isnan(v.rows[0].sd));
  EXPECT_EQ(v.rows[0].verdict, kOutside);
  EXPECT_EQ(seeds_wanted(v, 20), 3);  // two more measure a spread
}

}  // namespace
