// GA-BP network: the analytic Jacobian, learning a smooth function to held-out
// R^2 > 0.99, reproducibility from a seed, and the published GA-BP database.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/surrogate/gabp.hpp"
#include "demcal/surrogate/model_file.hpp"
#include "demcal/surrogate/neural_network_model.hpp"
#include "fixtures.hpp"

namespace {

using namespace demcal;
using namespace demcal::surrogate;

double smooth(double a, double b) { return std::sin(a) * std::cos(0.5 * b) + 0.3 * a * b; }

void smooth_data(int n, std::uint64_t seed, Eigen::MatrixXd& X, Eigen::MatrixXd& Y) {
  Rng rng(seed);
  X.resize(n, 2);
  Y.resize(n, 1);
  for (int i = 0; i < n; ++i) {
    X(i, 0) = rng.uniform(-2.0, 2.0);
    X(i, 1) = rng.uniform(-2.0, 2.0);
    Y(i, 0) = smooth(X(i, 0), X(i, 1));
  }
}

TEST(NeuralNetwork, JacobianMatchesFiniteDifferences) {
  NeuralNetwork net(3, 4, 2);
  Rng rng(3);
  for (Eigen::Index k = 0; k < net.parameters().size(); ++k) net.parameters()(k) = rng.uniform(-1, 1);
  Eigen::MatrixXd X = Eigen::MatrixXd::Random(5, 3), Y = Eigen::MatrixXd::Random(5, 2);
  Eigen::VectorXd r, r2;
  Eigen::MatrixXd J, unused;
  net.residuals_and_jacobian(X, Y, r, J);
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < net.parameters().size(); ++k) {
    NeuralNetwork moved = net;
    moved.parameters()(k) += h;
    moved.residuals_and_jacobian(X, Y, r2, unused);
    for (Eigen::Index i = 0; i < r.size(); ++i) EXPECT_NEAR(J(i, k), (r2(i) - r(i)) / h, 1e-5) << "param " << k;
  }
}

TEST(Gabp, LearnsASmoothFunctionOfTwoInputs) {
  Eigen::MatrixXd X, Y, Xtest, Ytest;
  smooth_data(120, 11, X, Y);
  smooth_data(200, 99, Xtest, Ytest);
  GabpOptions options;
  options.hidden = 8;
  options.seed = 5;
  GabpFit fit = fit_gabp({"a", "b"}, X, {"y"}, Y, options);
  EXPECT_EQ(fit.validation_rows.size(), 30u);
  EXPECT_GT(fit.validation[0].r2, 0.99);

  // Held-out points the training never saw, through the saved model.
  std::unique_ptr<Model> model = model_from_json(gabp_model_json(fit, "smooth"), "smooth");
  Eigen::MatrixXd predicted(Xtest.rows(), 1);
  for (Eigen::Index i = 0; i < Xtest.rows(); ++i) predicted(i, 0) = model->predict({Xtest(i, 0), Xtest(i, 1)})[0];
  std::vector<OutputQuality> q = prediction_quality({"y"}, Ytest, predicted);
  EXPECT_GT(q[0].r2, 0.99);
}

TEST(Gabp, SameSeedSameNetworkAndReloadPredictsIdentically) {
  Eigen::MatrixXd X, Y;
  smooth_data(60, 4, X, Y);
  GabpOptions options;
  options.seed = 42;
  options.ga_generations = 10;
  GabpFit a = fit_gabp({"a", "b"}, X, {"y"}, Y, options);
  GabpFit b = fit_gabp({"a", "b"}, X, {"y"}, Y, options);
  EXPECT_EQ(a.network.hidden(), b.network.hidden());
  EXPECT_EQ(a.network.parameters(), b.network.parameters());
  EXPECT_EQ(a.trials.size(), 10u);  // hidden = round(sqrt(2 + 1)) + 1..10

  nlohmann::json file = gabp_model_json(a, "smooth");
  std::unique_ptr<Model> reloaded = model_from_json(nlohmann::json::parse(file.dump()), "reloaded");
  std::unique_ptr<Model> direct = model_from_json(file, "direct");
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    std::vector<double> x{X(i, 0), X(i, 1)};
    EXPECT_EQ(reloaded->predict(x)[0], direct->predict(x)[0]);  // bit for bit
  }
}

TEST(Gabp, PublishedDatabaseOfHe2019) {
  std::vector<std::string> x = {"e_pp", "mu_pp", "e_pw", "mu_pw", "surface_energy_as_printed"};
  test::Fixture f = test::load_fixture("he2019_gabp_train.csv", x, "aor_deg");
  GabpOptions options;
  options.seed = 1;
  GabpFit fit = fit_gabp(x, f.X, {"aor_deg"}, Eigen::MatrixXd(f.y), options);
  EXPECT_EQ(fit.training_rows.size() + fit.validation_rows.size(), 80u);
  // The paper's engineering threshold for a usable surrogate is R^2 > 0.9.
  EXPECT_GT(fit.validation[0].r2, 0.9);
}

TEST(Gabp, ClearErrors) {
  Eigen::MatrixXd X, Y;
  smooth_data(20, 1, X, Y);
  GabpOptions options;
  options.validation_fraction = 0.0;
  EXPECT_THROW(fit_gabp({"a", "b"}, X, {"y"}, Y, options), Error);  // auto size needs validation
  options.validation_fraction = 1.5;
  EXPECT_THROW(fit_gabp({"a", "b"}, X, {"y"}, Y, options), Error);
}

}  // namespace
