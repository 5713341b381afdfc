// ANOVA and range analysis of designed experiments: a hand-worked L9 and the
// published 64-run concrete screening (Su et al. 2021), whose reference values
// were computed independently with statsmodels 0.13.5 (OLS on sum-coded
// categorical factors, anova_lm typ=3), i.e. Minitab's GLM with every column a term.
#include <gtest/gtest.h>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/design_anova.hpp"
#include "demcal/surrogate/range_analysis.hpp"
#include "fixtures.hpp"

namespace {

using namespace demcal;
using namespace demcal::surrogate;

const AnovaRow& row(const DesignAnova& a, const std::string& name) {
  for (const AnovaRow& r : a.terms)
    if (r.source == name) return r;
  throw std::runtime_error("no row " + name);
}

// Standard Taguchi L9(3^4); column D is left blank.
struct L9 {
  std::vector<std::string> names{"A", "B", "C", "D"};
  Eigen::MatrixXd X{9, 4};
  Eigen::VectorXd y{9};
  L9() {
    X << 1, 1, 1, 1, 1, 2, 2, 2, 1, 3, 3, 3, 2, 1, 2, 3, 2, 2, 3, 1, 2, 3, 1, 2, 3, 1, 3, 2, 3, 2, 1, 3, 3, 3, 2, 1;
    y << 10, 12, 14, 15, 18, 15, 21, 20, 24;
  }
};

// By hand: T = 149, CT = 149^2 / 9 = 2466.7778.
//   A: K = 36, 48, 65 -> SS = (36^2 + 48^2 + 65^2)/3 - CT = 2608.3333 - 2466.7778 = 141.5556
//   B: K = 46, 50, 53 -> SS = 2475.0000 - CT = 8.2222
//   C: K = 45, 51, 53 -> SS = 2478.3333 - CT = 11.5556
//   D: K = 52, 48, 49 -> SS = 2469.6667 - CT = 2.8889 (the error, 2 df)
//   Total = sum y^2 - CT = 2631 - 2466.7778 = 164.2222 = 141.5556 + 8.2222 + 11.5556 + 2.8889
//   F_A = (141.5556 / 2) / (2.8889 / 2) = 49.0
TEST(DesignAnova, HandWorkedL9WithABlankColumnAsError) {
  L9 l9;
  DesignAnovaOptions options;
  options.error_column = "D";
  DesignAnova a = design_anova(l9.names, l9.X, l9.y, {"A", "B", "C"}, "y", options);
  EXPECT_NEAR(row(a, "A").ss, 141.5555556, 1e-6);
  EXPECT_NEAR(row(a, "B").ss, 8.2222222, 1e-6);
  EXPECT_NEAR(row(a, "C").ss, 11.5555556, 1e-6);
  EXPECT_NEAR(a.error.ss, 2.8888889, 1e-6);
  EXPECT_EQ(a.error.df, 2);
  EXPECT_NEAR(a.total.ss, 164.2222222, 1e-6);
  EXPECT_NEAR(row(a, "A").f, 49.0, 1e-9);
  // P(F(2,2) > 49) = 1 / (1 + 49) for F(2,2).
  EXPECT_NEAR(row(a, "A").p, 1.0 / 50.0, 1e-12);
}

TEST(DesignAnova, SaturatedDesignWithoutAnErrorColumnSaysWhatToDo) {
  L9 l9;
  try {
    design_anova(l9.names, l9.X, l9.y, l9.names, "y", {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--error column:NAME"), std::string::npos) << e.what();
  }
}

TEST(DesignAnova, PoolingMovesSmallTermsIntoTheError) {
  L9 l9;
  DesignAnovaOptions options;
  options.error_column = "D";
  options.pool_below_f = 5.0;  // F_B = 2.85, F_C = 4.0 -> B pooled first, then C (F = 5.78 / (11.11/4) = 2.08)
  DesignAnova a = design_anova(l9.names, l9.X, l9.y, {"A", "B", "C"}, "y", options);
  EXPECT_TRUE(row(a, "B").pooled);
  EXPECT_TRUE(row(a, "C").pooled);
  EXPECT_FALSE(row(a, "A").pooled);
  EXPECT_EQ(a.error.df, 6);
  EXPECT_NEAR(a.error.ss, 2.8888889 + 8.2222222 + 11.5555556, 1e-6);
  EXPECT_NEAR(row(a, "A").f, (141.5555556 / 2) / (22.6666667 / 6), 1e-6);
}

TEST(DesignAnova, AliasedTermsAreNamed) {
  L9 l9;
  Eigen::MatrixXd X(9, 5);
  X << l9.X, l9.X.col(0);  // E repeats A
  try {
    design_anova({"A", "B", "C", "D", "E"}, X, l9.y, {"A", "E"}, "y", {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("term E is aliased"), std::string::npos) << e.what();
  }
}

TEST(DesignAnova, PublishedL64MatchesTheGeneralLinearModel) {
  test::Fixture f = test::load_fixture("su2021_L64_orthogonal.csv", test::l64_columns(), "sigma_u_MPa");
  DesignAnova a = design_anova(test::l64_columns(), f.X, f.y, test::l64_columns(), "sigma_u_MPa", {});
  ASSERT_EQ(a.terms.size(), 14u);
  EXPECT_EQ(a.error.df, 35);
  EXPECT_NEAR(a.error.ss, 1306.1618078125, 1e-8);
  EXPECT_NEAR(a.total.ss, 7559.6986484374993, 1e-8);
  EXPECT_NEAR(row(a, "pb_sigma_c_MPa").ss, 3162.9724515624912, 1e-8);
  EXPECT_NEAR(row(a, "pb_sigma_c_MPa").f, 42.3776116950201, 1e-9);
  EXPECT_NEAR(row(a, "pb_sigma_c_MPa").p, 4.477521035101012e-10, 1e-17);
  EXPECT_NEAR(row(a, "pb_tau_c_MPa").ss, 2747.2901265625032, 1e-8);
  EXPECT_NEAR(row(a, "pb_tau_c_MPa").p, 2.4717764070822877e-09, 1e-16);
  EXPECT_NEAR(row(a, "mu").p, 0.32835637229987219, 1e-12);
  EXPECT_NEAR(row(a, "null_column").ss, 7.6313171875003185, 1e-8);
  // The published conclusion: the two mortar bond strengths dominate sigma_u.
  for (const AnovaRow& r : a.terms)
    EXPECT_EQ(r.p < 0.01, r.source == "pb_sigma_c_MPa" || r.source == "pb_tau_c_MPa") << r.source;

  test::Fixture e = test::load_fixture("su2021_L64_orthogonal.csv", test::l64_columns(), "E_GPa");
  DesignAnova ae = design_anova(test::l64_columns(), e.X, e.y, test::l64_columns(), "E_GPa", {});
  EXPECT_NEAR(row(ae, "Ec_GPa").ss, 11349.280278124997, 1e-7);
  EXPECT_NEAR(row(ae, "Ec_GPa").f, 3004.5886020775552, 1e-7);
  EXPECT_NEAR(row(ae, "kn_ks").p, 2.0797783814273758e-21, 1e-28);
  EXPECT_NEAR(row(ae, "Ec_j_GPa").ss, 185.29205312499985, 1e-9);
  EXPECT_NEAR(row(ae, "null_column").f, 31.325737535945468, 1e-8);
  EXPECT_NEAR(ae.error.ss, 66.103028125000137, 1e-9);

  test::Fixture n = test::load_fixture("su2021_L64_orthogonal.csv", test::l64_columns(), "nu");
  DesignAnova an = design_anova(test::l64_columns(), n.X, n.y, test::l64_columns(), "nu", {});
  EXPECT_NEAR(row(an, "kn_ks").ss, 0.6581529218749993, 1e-12);
  EXPECT_NEAR(row(an, "mu").p, 0.00027072000486717156, 1e-12);
  EXPECT_NEAR(an.error.ss, 0.010310328125000009, 1e-14);
}

TEST(DesignAnova, PublishedL64WithTheBlankColumnAsError) {
  test::Fixture f = test::load_fixture("su2021_L64_orthogonal.csv", test::l64_columns(), "sigma_u_MPa");
  DesignAnovaOptions options;
  options.error_column = "null_column";
  DesignAnova a = design_anova(test::l64_columns(), f.X, f.y, test::l64_columns(), "sigma_u_MPa", options);
  ASSERT_EQ(a.terms.size(), 13u);
  EXPECT_EQ(a.error.df, 2);
  EXPECT_NEAR(a.error.ss, 7.6313171875000485, 1e-8);
  EXPECT_NEAR(row(a, "pb_sigma_c_MPa").f, 414.47267540437008, 1e-6);
  EXPECT_NEAR(row(a, "pb_sigma_c_MPa").p, 0.0024068971540107246, 1e-12);
  EXPECT_NEAR(row(a, "pb_sigma_c_j_MPa").p, 0.04760464205503686, 1e-12);
}

TEST(RangeAnalysis, HandWorkedL9) {
  L9 l9;
  RangeAnalysis r = range_analysis({"A", "B", "C"}, l9.X.leftCols(3), l9.y, "y");
  ASSERT_EQ(r.factors.size(), 3u);
  const FactorRange& a = r.factors[0];
  EXPECT_DOUBLE_EQ(a.levels[0].sum, 36);
  EXPECT_DOUBLE_EQ(a.levels[2].sum, 65);
  EXPECT_DOUBLE_EQ(a.levels[1].mean, 16);
  EXPECT_NEAR(a.range, 65.0 / 3 - 12, 1e-12);
  EXPECT_EQ(a.rank, 1);
  EXPECT_EQ(r.factors[1].rank, 3);  // B: R = 53/3 - 46/3 = 2.33
  EXPECT_EQ(r.factors[2].rank, 2);  // C: R = 53/3 - 15 = 2.67
  EXPECT_DOUBLE_EQ(a.best_level, 3);
}

TEST(RangeAnalysis, PublishedL64LevelSumsWithUnequalCounts) {
  test::Fixture f = test::load_fixture("su2021_L64_orthogonal.csv", test::l64_columns(), "sigma_u_MPa");
  RangeAnalysis r = range_analysis(test::l64_columns(), f.X, f.y, "sigma_u_MPa");
  const FactorRange& ec = r.factors[0];
  ASSERT_EQ(ec.levels.size(), 3u);
  EXPECT_EQ(ec.levels[0].count, 32);
  EXPECT_EQ(ec.levels[1].count, 16);
  EXPECT_NEAR(ec.levels[0].sum, 942.35, 1e-9);
  EXPECT_NEAR(ec.levels[2].mean, 30.025625, 1e-12);
  EXPECT_NEAR(ec.range, 1.0796875, 1e-12);
  EXPECT_EQ(r.factors[2].rank, 1);  // pb_sigma_c_MPa
  EXPECT_EQ(r.factors[3].rank, 2);  // pb_tau_c_MPa
}

TEST(RangeAnalysis, RejectsColumnsThatAreNotDesignFactors) {
  Eigen::MatrixXd X(4, 1);
  X << 1, 2, 3, 4;
  Eigen::VectorXd y(4);
  y << 1, 2, 3, 4;
  EXPECT_THROW(range_analysis({"x"}, X, y, "y"), Error);
  X << 1, 1, 1, 1;
  EXPECT_THROW(range_analysis({"x"}, X, y, "y"), Error);
}

}  // namespace
