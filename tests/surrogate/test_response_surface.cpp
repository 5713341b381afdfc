// Response surfaces: closed-form checks (an exact quadratic is recovered,
// PRESS equals leave-one-out refits) and the three published response-surface
// runs of Su et al. (2021). Reference values for the fixtures were computed
// independently with statsmodels 0.13.5 OLS (adjusted SS by extra sums of
// squares, PRESS from the hat matrix), i.e. what Minitab's response-surface
// analysis prints.
#include <gtest/gtest.h>

#include "../common/error_of.hpp"

#include "demcal/core/error.hpp"
#include "demcal/doe/response_surface.hpp"
#include "demcal/surrogate/response_surface.hpp"
#include "fixtures.hpp"

using demcal::test::error_of;

namespace {

using namespace demcal;
using namespace demcal::surrogate;

double coefficient(const std::vector<CoefficientRow>& rows, const std::string& term) {
  for (const CoefficientRow& r : rows)
    if (r.term == term) return r.coef;
  throw std::runtime_error("no term " + term);
}

const AnovaRow& anova_row(const SurfaceFit& fit, const std::string& source) {
  for (const AnovaRow& r : fit.anova)
    if (r.source == source) return r;
  throw std::runtime_error("no row " + source);
}


TEST(ResponseSurface, RecoversAnExactQuadraticOnABoxBehnkenDesign) {
  doe::Design design = doe::box_behnken(3, -1);
  Eigen::MatrixXd X = design.coded * 5.0;  // natural range [-5, 5]
  X.col(0).array() += 20.0;
  Eigen::VectorXd y(X.rows());
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    double a = X(i, 0), b = X(i, 1), c = X(i, 2);
    y(i) = 3.0 - 2.0 * a + 0.5 * b + 4.0 * c + 0.25 * a * a - 1.5 * b * b + 0.75 * a * b - 0.125 * b * c;
  }
  SurfaceFit fit = fit_surface({"A", "B", "C"}, X, y, "y", {});
  EXPECT_NEAR(coefficient(fit.natural, "1"), 3.0, 1e-9);
  EXPECT_NEAR(coefficient(fit.natural, "A"), -2.0, 1e-10);
  EXPECT_NEAR(coefficient(fit.natural, "C"), 4.0, 1e-10);
  EXPECT_NEAR(coefficient(fit.natural, "A^2"), 0.25, 1e-12);
  EXPECT_NEAR(coefficient(fit.natural, "B^2"), -1.5, 1e-12);
  EXPECT_NEAR(coefficient(fit.natural, "C^2"), 0.0, 1e-12);
  EXPECT_NEAR(coefficient(fit.natural, "A*B"), 0.75, 1e-12);
  EXPECT_NEAR(coefficient(fit.natural, "B*C"), -0.125, 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
  // The three centre points repeat exactly, as deterministic DEM runs with one seed do:
  // no pure error, so no lack-of-fit test, and the fit says why.
  EXPECT_NE(fit.note.find("no pure error"), std::string::npos);
  for (const AnovaRow& r : fit.anova) EXPECT_NE(r.source, "Lack-of-Fit");
  double x[3] = {21.0, -2.0, 3.0};
  EXPECT_NEAR(predict_surface(fit, x), 3.0 - 42.0 - 1.0 + 12.0 + 0.25 * 441 - 6.0 - 31.5 + 0.75, 1e-9);
}

TEST(ResponseSurface, PressEqualsLeaveOneOutRefits) {
  test::Fixture f = test::load_fixture("su2021_CCD2_sigma_u.csv", {"pb_sigma_c_MPa", "pb_tau_c_MPa"}, "sigma_u_MPa");
  SurfaceFit fit = fit_surface({"A", "B"}, f.X, f.y, "y", {});
  double press = 0.0;
  for (Eigen::Index out = 0; out < f.X.rows(); ++out) {
    Eigen::MatrixXd X(f.X.rows() - 1, 2);
    Eigen::VectorXd y(f.X.rows() - 1);
    for (Eigen::Index i = 0, k = 0; i < f.X.rows(); ++i)
      if (i != out) {
        X.row(k) = f.X.row(i);
        y(k++) = f.y(i);
      }
    SurfaceFit loo = fit_surface({"A", "B"}, X, y, "y", {});
    double x[2] = {f.X(out, 0), f.X(out, 1)};
    double e = f.y(out) - predict_surface(loo, x);
    EXPECT_NEAR(fit.press_residuals(out), e, 1e-9);
    press += e * e;
  }
  EXPECT_NEAR(fit.press, press, 1e-8);
}

TEST(ResponseSurface, PublishedCcdForSigmaU) {
  test::Fixture f = test::load_fixture("su2021_CCD2_sigma_u.csv", {"pb_sigma_c_MPa", "pb_tau_c_MPa"}, "sigma_u_MPa");
  SurfaceOptions options;
  options.coding = {{20, 10}, {20, 10}};  // Minitab codes the CCD cube (10, 30) as -1/+1
  SurfaceFit fit = fit_surface({"pb_sigma_c_MPa", "pb_tau_c_MPa"}, f.X, f.y, "sigma_u_MPa", options);
  EXPECT_NEAR(fit.r2, 0.98813142478526328, 1e-12);
  EXPECT_NEAR(fit.r2_adj, 0.97965387106045143, 1e-12);
  EXPECT_NEAR(fit.r2_pred, 0.93869881177548753, 1e-10);
  EXPECT_NEAR(fit.s, 1.9419856387077408, 1e-11);
  EXPECT_NEAR(coefficient(fit.natural, "1"), -0.48124619543485636, 1e-9);
  EXPECT_NEAR(coefficient(fit.natural, "pb_sigma_c_MPa"), 1.0828939657674588, 1e-11);
  EXPECT_NEAR(coefficient(fit.natural, "pb_tau_c_MPa^2"), -0.030181475862615777, 1e-13);
  EXPECT_NEAR(coefficient(fit.natural, "pb_sigma_c_MPa*pb_tau_c_MPa"), 0.066025, 1e-13);
  EXPECT_NEAR(coefficient(fit.coded, "pb_sigma_c_MPa"), 11.48134010605162, 1e-10);
  EXPECT_NEAR(fit.coded[1].se, 0.68659889929818152, 1e-11);
  EXPECT_NEAR(fit.coded[1].p, 6.6885715529190065e-07, 1e-15);
  EXPECT_NEAR(fit.natural[1].p, 0.019577725672906471, 1e-12);
  EXPECT_NEAR(anova_row(fit, "Model").f, 116.55855649646, 1e-8);
  EXPECT_NEAR(anova_row(fit, "Square").ss, 116.67074363388859, 1e-9);
  EXPECT_NEAR(anova_row(fit, "pb_sigma_c_MPa").ss, 1054.5592517264245, 1e-8);
  EXPECT_EQ(anova_row(fit, "Lack-of-Fit").df, 3);
  EXPECT_NEAR(anova_row(fit, "Lack-of-Fit").p, 0.20161072544733125, 1e-11);
  EXPECT_NEAR(anova_row(fit, "Pure Error").ss, 9.2591999999999963, 1e-10);

  // The data's own range as coding changes the coded coefficients, not the tests.
  SurfaceFit data_coded = fit_surface({"pb_sigma_c_MPa", "pb_tau_c_MPa"}, f.X, f.y, "sigma_u_MPa", {});
  EXPECT_NEAR(coefficient(data_coded.coded, "pb_sigma_c_MPa"), 16.236911177978204, 1e-9);
  EXPECT_NEAR(data_coded.coded[1].t, fit.coded[1].t, 1e-9);
  EXPECT_NEAR(coefficient(data_coded.natural, "pb_sigma_c_MPa"), coefficient(fit.natural, "pb_sigma_c_MPa"), 1e-11);
}

TEST(ResponseSurface, PublishedBoxBehnkenForE) {
  test::Fixture f = test::load_fixture("su2021_BBD5_E.csv", {"Ec_GPa", "kn_ks", "mu", "Ec_j_GPa", "kn_ks_j"}, "E_GPa");
  SurfaceFit fit = fit_surface({"Ec_GPa", "kn_ks", "mu", "Ec_j_GPa", "kn_ks_j"}, f.X, f.y, "E_GPa", {});
  ASSERT_EQ(fit.terms.size(), 21u);
  EXPECT_NEAR(fit.r2, 0.99812603502133013, 1e-12);
  EXPECT_NEAR(fit.r2_adj, 0.99662686303839432, 1e-12);
  EXPECT_NEAR(fit.r2_pred, 0.99527455821848831, 1e-11);
  EXPECT_NEAR(fit.press, 20.886665653332916, 1e-8);
  EXPECT_NEAR(coefficient(fit.natural, "Ec_GPa"), 1.9984479166666458, 1e-10);
  EXPECT_NEAR(coefficient(fit.natural, "kn_ks^2"), 0.79718518518518722, 1e-10);
  EXPECT_NEAR(coefficient(fit.natural, "Ec_GPa*kn_ks"), -0.14923333333333391, 1e-11);
  EXPECT_NEAR(anova_row(fit, "2-Way Interaction").ss, 28.509355000000017, 1e-8);
  EXPECT_NEAR(anova_row(fit, "Ec_GPa*Ec_j_GPa").p, 0.00023128231943778094, 1e-12);
  EXPECT_EQ(anova_row(fit, "Lack-of-Fit").df, 20);
  EXPECT_NEAR(anova_row(fit, "Lack-of-Fit").f, 0.18290851008740719, 1e-9);
  EXPECT_EQ(anova_row(fit, "Pure Error").df, 5);
}

TEST(ResponseSurface, PublishedBoxBehnkenForNu) {
  test::Fixture f = test::load_fixture("su2021_BBD4_nu.csv", {"Ec_GPa", "kn_ks", "mu", "kn_ks_j"}, "nu");
  SurfaceFit fit = fit_surface({"Ec_GPa", "kn_ks", "mu", "kn_ks_j"}, f.X, f.y, "nu", {});
  EXPECT_NEAR(fit.r2, 0.99113278092158441, 1e-12);
  EXPECT_NEAR(fit.r2_adj, 0.9807876919967663, 1e-12);
  EXPECT_NEAR(fit.r2_pred, 0.9767133185125304, 1e-11);
  EXPECT_NEAR(coefficient(fit.natural, "mu"), -0.158166666666665, 1e-12);
  EXPECT_NEAR(anova_row(fit, "kn_ks").f, 1217.8310322156465, 1e-7);
  EXPECT_NEAR(anova_row(fit, "Lack-of-Fit").p, 0.9999858651256659, 1e-11);
  // Variance inflation of a Box-Behnken: 1 for linear and interaction terms, 1.25 for squares here.
  EXPECT_NEAR(fit.coded[1].vif, 1.0, 1e-12);
  EXPECT_NEAR(fit.coded[5].vif, 1.25, 1e-12);
  EXPECT_NEAR(fit.coded[9].vif, 1.0, 1e-12);

  SurfaceOptions linear;
  linear.kind = SurfaceKind::Linear;
  SurfaceFit lin = fit_surface({"Ec_GPa", "kn_ks", "mu", "kn_ks_j"}, f.X, f.y, "nu", linear);
  EXPECT_NEAR(lin.r2, 0.9263358155587339, 1e-12);
  EXPECT_NEAR(lin.r2_pred, 0.88777616136557524, 1e-11);
}

TEST(ResponseSurface, BackwardEliminationKeepsHierarchy) {
  test::Fixture f = test::load_fixture("su2021_BBD4_nu.csv", {"Ec_GPa", "kn_ks", "mu", "kn_ks_j"}, "nu");
  SurfaceOptions options;
  options.eliminate_alpha = 0.05;
  SurfaceFit fit = fit_surface({"Ec_GPa", "kn_ks", "mu", "kn_ks_j"}, f.X, f.y, "nu", options);
  EXPECT_FALSE(fit.eliminated.empty());
  // Every kept square or interaction has its linear terms.
  for (const SurfaceTerm& t : fit.terms)
    for (int factor : t.factors) {
      bool has_linear = false;
      for (const SurfaceTerm& u : fit.terms) has_linear = has_linear || (u.factors.size() == 1 && u.factors[0] == factor);
      EXPECT_TRUE(has_linear) << t.name;
    }
  // Every kept term that hierarchy does not protect is significant.
  for (std::size_t t = 1; t < fit.terms.size(); ++t) {
    bool protected_term = false;
    if (fit.terms[t].factors.size() == 1) {
      for (const SurfaceTerm& u : fit.terms) {
        bool contains = u.factors.size() == 2 &&
                        (u.factors[0] == fit.terms[t].factors[0] || u.factors[1] == fit.terms[t].factors[0]);
        protected_term = protected_term || contains;
      }
    }
    if (!protected_term) {
      EXPECT_LT(fit.coded[t].p, 0.05) << fit.terms[t].name;
    }
  }
  EXPECT_GT(fit.r2_adj, 0.98);
}

TEST(ResponseSurface, ClearErrors) {
  Eigen::MatrixXd X(8, 3);
  X.setRandom();
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(8, 0, 1);
  std::string message = error_of([&]() { fit_surface({"A", "B", "C"}, X, y, "y", {}); });
  EXPECT_NE(message.find("has 10 terms and needs at least 11 runs"), std::string::npos) << message;
  EXPECT_NE(message.find("the data has 8"), std::string::npos) << message;

  Eigen::MatrixXd constant = Eigen::MatrixXd::Random(20, 2);
  constant.col(1).setConstant(3.0);
  message = error_of([&]() { fit_surface({"A", "B"}, constant, Eigen::VectorXd::Random(20), "y", {}); });
  EXPECT_NE(message.find("column B is constant"), std::string::npos) << message;

  // A 2-level factorial cannot estimate squares.
  Eigen::MatrixXd two_level(9, 2);
  two_level << -1, -1, 1, -1, -1, 1, 1, 1, -1, -1, 1, -1, -1, 1, 1, 1, -1, 1;
  message = error_of([&]() { fit_surface({"A", "B"}, two_level, Eigen::VectorXd::Random(9), "y", {}); });
  EXPECT_NE(message.find("cannot estimate term(s) A^2, B^2"), std::string::npos) << message;
}

}  // namespace
