// Saved models: reload round trips predict identical numbers, the domain is
// reported, and malformed files give errors naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/model_file.hpp"
#include "demcal/surrogate/response_surface_model.hpp"
#include "fixtures.hpp"

namespace {

using namespace demcal;
using namespace demcal::surrogate;

TEST(ModelFile, ResponseSurfaceReloadsAndPredictsIdentically) {
  std::vector<std::string> x = {"Ec_GPa", "kn_ks", "mu", "Ec_j_GPa", "kn_ks_j"};
  test::Fixture f = test::load_fixture("su2021_BBD5_E.csv", x, "E_GPa");
  SurfaceFit fit = fit_surface(x, f.X, f.y, "E_GPa", {});
  std::string path = ::testing::TempDir() + "demcal_model_e.json";
  save_model(surface_model_json({fit}, "bbd.csv"), path);
  std::unique_ptr<Model> model = load_model(path);
  ASSERT_EQ(model->inputs(), x);
  ASSERT_EQ(model->outputs(), std::vector<std::string>{"E_GPa"});
  EXPECT_DOUBLE_EQ(model->domain()[0].low, 10.0);
  EXPECT_DOUBLE_EQ(model->domain()[0].high, 30.0);
  for (Eigen::Index i = 0; i < f.X.rows(); ++i) {
    std::vector<double> row(f.X.row(i).data(), f.X.row(i).data() + 0);
    for (Eigen::Index j = 0; j < f.X.cols(); ++j) row.push_back(f.X(i, j));
    EXPECT_EQ(model->predict(row)[0], predict_surface(fit, row.data()));
    EXPECT_NEAR(model->predict(row)[0], fit.fitted(i), 1e-9);
  }
  EXPECT_TRUE(model->outside_domain({20, 2.5, 1, 10, 2.5}).empty());
  EXPECT_EQ(model->outside_domain({35, 2.5, 1, 10, 0.5}), (std::vector<std::string>{"Ec_GPa", "kn_ks_j"}));

  nlohmann::json file = nlohmann::json::parse(std::ifstream(path));
  EXPECT_EQ(file["kind"], "quadratic");
  EXPECT_TRUE(file["coefficients"].contains("Ec_GPa*kn_ks"));
  EXPECT_TRUE(file["coefficients"].contains("mu^2"));
  EXPECT_NEAR(file["r2_pred"].get<double>(), 0.99527455821848831, 1e-11);
}

TEST(ModelFile, SeveralResponsesInOneFile) {
  test::Fixture f = test::load_fixture("su2021_CCD2_sigma_u.csv", {"pb_sigma_c_MPa", "pb_tau_c_MPa"}, "sigma_u_MPa");
  SurfaceOptions linear;
  linear.kind = SurfaceKind::Linear;
  SurfaceFit a = fit_surface({"pb_sigma_c_MPa", "pb_tau_c_MPa"}, f.X, f.y, "sigma_u_MPa", linear);
  SurfaceFit b = fit_surface({"pb_sigma_c_MPa", "pb_tau_c_MPa"}, f.X, 2.0 * f.y, "twice", linear);
  std::unique_ptr<Model> model = model_from_json(surface_model_json({a, b}, "ccd.csv"), "two");
  std::vector<double> y = model->predict({20, 20});
  ASSERT_EQ(y.size(), 2u);
  EXPECT_NEAR(y[1], 2 * y[0], 1e-9);
}

TEST(ModelFile, PredictionIntervalOfAStraightLineMatchesTheClosedForm) {
  // y ~ a + b x on x = 1..6: a new observation at x0 has the 95 % interval
  // yhat -+ t(0.975, n - 2) s sqrt(1 + 1/n + (x0 - xbar)^2 / Sxx) (Montgomery & Runger, eq. 11-33).
  Eigen::MatrixXd X(6, 1);
  Eigen::VectorXd y(6);
  const double ys[] = {2.1, 3.9, 6.2, 7.8, 10.1, 12.2};
  for (int i = 0; i < 6; ++i) {
    X(i, 0) = i + 1;
    y(i) = ys[i];
  }
  SurfaceOptions linear;
  linear.kind = SurfaceKind::Linear;
  SurfaceFit fit = fit_surface({"x"}, X, y, "y", linear);
  std::unique_ptr<Model> model = model_from_json(nlohmann::json::parse(surface_model_json({fit}, "line").dump()), "line");
  const double x0 = 8.0, xbar = 3.5, sxx = 17.5, t4 = 2.7764451051977987;
  double low = 0, high = 0;
  ASSERT_TRUE(model->prediction_interval_95(&x0, &low, &high));
  const double yhat = model->predict({x0})[0];
  const double half = t4 * fit.s * std::sqrt(1.0 + 1.0 / 6.0 + (x0 - xbar) * (x0 - xbar) / sxx);
  EXPECT_NEAR(low, yhat - half, 1e-9);
  EXPECT_NEAR(high, yhat + half, 1e-9);
  // A file written before intervals were kept gives none, and says so by returning false.
  nlohmann::json old = surface_model_json({fit}, "line");
  old["responses"][0].erase("prediction_interval");
  EXPECT_FALSE(model_from_json(old, "old")->prediction_interval_95(&x0, &low, &high));
}

TEST(ModelFile, ErrorsNameTheFile) {
  auto message = [](const nlohmann::json& j) {
    try {
      model_from_json(j, "m.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({{"kind", "spline"}}).find("m.json: unknown model kind \"spline\" (known: gabp, linear, quadratic)"),
            std::string::npos)
      << message({{"kind", "spline"}});
  EXPECT_NE(message({{"x", 1}}).find("not a demcal model"), std::string::npos);
  EXPECT_NE(message({{"kind", "quadratic"}, {"inputs", nlohmann::json::array()}}).find("m.json"), std::string::npos);
  EXPECT_THROW(load_model("/nonexistent/model.json"), Error);
}

}  // namespace
