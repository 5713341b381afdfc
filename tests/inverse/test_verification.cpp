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
  std::string md = verification_markdown(v);
  EXPECT_NE(md.find("| sigma_u_MPa | 30 | 30.5 | 30 | 1 | 3.33 | 0.00 | yes |"), std::string::npos) << md;
  EXPECT_NE(md.find("seed 4 failed: unstable"), std::string::npos) << md;
  EXPECT_EQ(verification_json(v)["outputs"]["E_GPa"]["passed"], false);
}

TEST(Verification, OneSeedCannotPass) {
  Verification v = verify({{"nu", 0.2}}, {}, {{1, true, "", {{"nu", 0.2}}}}, 0.05);
  EXPECT_FALSE(v.passed);  // no spread from a single run
  EXPECT_TRUE(std::isnan(v.rows[0].sd));
}

}  // namespace
