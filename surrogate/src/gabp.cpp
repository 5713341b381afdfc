#include "demcal/surrogate/gabp.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/rng.hpp"

namespace demcal::surrogate {

namespace {

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& M, const std::vector<int>& rows) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), M.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = M.row(rows[i]);
  return out;
}

double mse(const NeuralNetwork& net, const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  if (X.rows() == 0) return 0.0;
  return (net.forward(X) - Y).squaredNorm() / static_cast<double>(Y.size());
}

// Real-coded GA over the parameter vector: tournament selection, blend
// crossover, Gaussian mutation, two elites. Returns the best genome.
Eigen::VectorXd genetic_initial_weights(NeuralNetwork net, const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y,
                                        const GabpOptions& o, Rng& rng, double& best_mse) {
  const int P = net.parameter_count();
  const int N = std::max(4, o.ga_population);
  const double bound = o.ga_weight_bound;
  std::vector<Eigen::VectorXd> population(static_cast<std::size_t>(N), Eigen::VectorXd(P));
  std::vector<double> fitness(static_cast<std::size_t>(N));
  for (auto& genome : population)
    for (int k = 0; k < P; ++k) genome(k) = rng.uniform(-bound, bound);
  auto evaluate = [&](const Eigen::VectorXd& genome) {
    net.parameters() = genome;
    double e = mse(net, X, Y);
    return std::isfinite(e) ? e : 1e300;
  };
  for (int i = 0; i < N; ++i) fitness[static_cast<std::size_t>(i)] = evaluate(population[static_cast<std::size_t>(i)]);
  auto tournament = [&]() -> const Eigen::VectorXd& {
    std::size_t a = rng.below(static_cast<std::uint64_t>(N)), b = rng.below(static_cast<std::uint64_t>(N));
    return fitness[a] <= fitness[b] ? population[a] : population[b];
  };
  const double mutation_rate = 1.0 / P, mutation_sigma = 0.1 * bound;
  for (int g = 0; g < o.ga_generations; ++g) {
    std::vector<std::size_t> order(static_cast<std::size_t>(N));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return fitness[a] < fitness[b]; });
    std::vector<Eigen::VectorXd> next;
    std::vector<double> next_fitness;
    for (int e = 0; e < 2; ++e) {
      next.push_back(population[order[static_cast<std::size_t>(e)]]);
      next_fitness.push_back(fitness[order[static_cast<std::size_t>(e)]]);
    }
    while (static_cast<int>(next.size()) < N) {
      Eigen::VectorXd child = tournament();
      if (rng.uniform() < 0.8) {
        const Eigen::VectorXd& other = tournament();
        for (int k = 0; k < P; ++k) {
          double w = rng.uniform(-0.25, 1.25);  // BLX-0.25
          child(k) = w * child(k) + (1.0 - w) * other(k);
        }
      }
      for (int k = 0; k < P; ++k)
        if (rng.uniform() < mutation_rate) child(k) += rng.normal(0.0, mutation_sigma);
      child = child.cwiseMax(-2 * bound).cwiseMin(2 * bound);
      next_fitness.push_back(evaluate(child));
      next.push_back(std::move(child));
    }
    population = std::move(next);
    fitness = std::move(next_fitness);
  }
  auto best = std::min_element(fitness.begin(), fitness.end()) - fitness.begin();
  best_mse = fitness[static_cast<std::size_t>(best)];
  return population[static_cast<std::size_t>(best)];
}

struct LmResult {
  int epochs = 0;
  std::string stop_reason;
};

// Levenberg-Marquardt (MATLAB trainlm's mu schedule) with early stopping:
// the parameters with the lowest validation error are kept.
LmResult train_lm(NeuralNetwork& net, const Eigen::MatrixXd& Xt, const Eigen::MatrixXd& Yt, const Eigen::MatrixXd& Xv,
                  const Eigen::MatrixXd& Yv, const GabpOptions& o) {
  const bool early_stopping = Xv.rows() > 0;
  double mu = 1e-3;
  Eigen::VectorXd r, r_try;
  Eigen::MatrixXd J, J_try;
  net.residuals_and_jacobian(Xt, Yt, r, J);
  double sse = r.squaredNorm();
  Eigen::VectorXd best = net.parameters();
  double best_validation = early_stopping ? mse(net, Xv, Yv) : sse;
  int fails = 0;
  LmResult result;
  result.stop_reason = "maximum epochs";
  for (int epoch = 1; epoch <= o.lm_max_epochs; ++epoch) {
    result.epochs = epoch;
    Eigen::MatrixXd H = J.transpose() * J;
    Eigen::VectorXd g = J.transpose() * r;
    if (g.norm() < 1e-10) {
      result.stop_reason = "gradient below 1e-10";
      break;
    }
    bool improved = false;
    Eigen::VectorXd current = net.parameters();
    while (mu <= 1e10) {
      Eigen::MatrixXd A = H;
      A.diagonal().array() += mu;
      Eigen::VectorXd step = A.ldlt().solve(-g);
      net.parameters() = current + step;
      net.residuals_and_jacobian(Xt, Yt, r_try, J_try);
      double sse_try = r_try.squaredNorm();
      if (std::isfinite(sse_try) && sse_try < sse) {
        improved = true;
        sse = sse_try;
        r.swap(r_try);
        J.swap(J_try);
        mu = std::max(mu * 0.1, 1e-20);
        break;
      }
      mu *= 10.0;
    }
    if (!improved) {
      net.parameters() = current;
      result.stop_reason = "mu above 1e10";
      break;
    }
    double validation = early_stopping ? mse(net, Xv, Yv) : sse;
    if (validation < best_validation) {
      best_validation = validation;
      best = net.parameters();
      fails = 0;
    } else if (early_stopping && ++fails >= o.lm_max_fail) {
      result.stop_reason = "validation error rose for " + std::to_string(o.lm_max_fail) + " epochs";
      break;
    }
    if (sse / static_cast<double>(r.size()) < 1e-14) {
      result.stop_reason = "training error below 1e-14";
      break;
    }
  }
  net.parameters() = best;
  return result;
}

struct Trained {
  NeuralNetwork net{1, 1, 1};
  double ga_mse = 0.0;
  LmResult lm;
};

Trained train(int hidden, const Eigen::MatrixXd& Xt, const Eigen::MatrixXd& Yt, const Eigen::MatrixXd& Xv,
              const Eigen::MatrixXd& Yv, const GabpOptions& o, std::uint64_t stream) {
  Trained t;
  t.net = NeuralNetwork(static_cast<int>(Xt.cols()), hidden, static_cast<int>(Yt.cols()));
  Rng rng(o.seed, stream);
  t.net.parameters() = genetic_initial_weights(t.net, Xt, Yt, o, rng, t.ga_mse);
  t.lm = train_lm(t.net, Xt, Yt, Xv, Yv, o);
  return t;
}

Eigen::MatrixXd unscale(const MinMaxScaling& s, const Eigen::MatrixXd& M) {
  Eigen::MatrixXd out(M.rows(), M.cols());
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = 0; j < M.cols(); ++j) out(i, j) = s.from_unit(j, M(i, j));
  return out;
}

}  // namespace

std::vector<OutputQuality> prediction_quality(const std::vector<std::string>& names, const Eigen::MatrixXd& observed,
                                              const Eigen::MatrixXd& predicted) {
  std::vector<OutputQuality> quality;
  for (Eigen::Index j = 0; j < observed.cols(); ++j) {
    OutputQuality q;
    q.output = names[static_cast<std::size_t>(j)];
    double mean = observed.col(j).mean();
    double ss_res = (observed.col(j) - predicted.col(j)).squaredNorm();
    double ss_tot = (observed.col(j).array() - mean).square().sum();
    q.r2 = ss_tot > 0 ? 1.0 - ss_res / ss_tot : std::numeric_limits<double>::quiet_NaN();
    q.rmse = observed.rows() > 0 ? std::sqrt(ss_res / static_cast<double>(observed.rows())) : 0.0;
    quality.push_back(q);
  }
  return quality;
}

GabpFit fit_gabp(const std::vector<std::string>& inputs, const Eigen::MatrixXd& X,
                 const std::vector<std::string>& outputs, const Eigen::MatrixXd& Y, const GabpOptions& options) {
  const Eigen::Index n = X.rows();
  if (!(options.validation_fraction >= 0.0 && options.validation_fraction < 1.0))
    throw Error("gabp: --validation-fraction must be in [0, 1)");
  if (options.hidden < 0) throw Error("gabp: --hidden must be auto or a positive integer");
  if (options.ga_population < 4 || options.ga_generations < 0)
    throw Error("gabp: the GA needs a population of at least 4 and generations >= 0");
  const auto n_validation = static_cast<Eigen::Index>(std::lround(options.validation_fraction * static_cast<double>(n)));
  if (options.hidden == 0 && n_validation == 0)
    throw Error("gabp: --hidden auto chooses the size by validation R^2 and needs a validation split (--validation-fraction > 0)");
  if (n - n_validation < 3)
    throw Error("gabp: only " + std::to_string(n - n_validation) + " training rows; need at least 3");

  GabpFit fit;
  fit.options = options;
  fit.inputs = inputs;
  fit.outputs = outputs;
  fit.input_scaling = MinMaxScaling::of_columns(X);
  fit.output_scaling = MinMaxScaling::of_columns(Y);
  for (std::size_t j = 0; j < inputs.size(); ++j)
    fit.domain.push_back({inputs[j], fit.input_scaling.min(static_cast<Eigen::Index>(j)),
                          fit.input_scaling.max(static_cast<Eigen::Index>(j))});

  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  Rng split_rng(options.seed, 0x5e1f);
  split_rng.shuffle(order);
  fit.validation_rows.assign(order.begin(), order.begin() + n_validation);
  fit.training_rows.assign(order.begin() + n_validation, order.end());
  std::sort(fit.validation_rows.begin(), fit.validation_rows.end());
  std::sort(fit.training_rows.begin(), fit.training_rows.end());

  Eigen::MatrixXd Xs = fit.input_scaling.to_unit(X), Ys = fit.output_scaling.to_unit(Y);
  Eigen::MatrixXd Xt = rows_of(Xs, fit.training_rows), Yt = rows_of(Ys, fit.training_rows);
  Eigen::MatrixXd Xv = rows_of(Xs, fit.validation_rows), Yv = rows_of(Ys, fit.validation_rows);

  std::vector<int> sizes;
  if (options.hidden > 0) {
    sizes.push_back(options.hidden);
  } else {
    int base = static_cast<int>(std::lround(std::sqrt(static_cast<double>(inputs.size() + outputs.size()))));
    for (int a = 1; a <= 10; ++a) sizes.push_back(base + a);
  }
  double best_score = -std::numeric_limits<double>::infinity();
  for (int hidden : sizes) {
    Trained t = train(hidden, Xt, Yt, Xv, Yv, options, static_cast<std::uint64_t>(hidden));
    HiddenTrial trial;
    trial.hidden = hidden;
    trial.training_mse = mse(t.net, Xt, Yt);
    trial.epochs = t.lm.epochs;
    double score = 0.0;
    if (Xv.rows() > 0) {
      auto q = prediction_quality(outputs, rows_of(Y, fit.validation_rows), unscale(fit.output_scaling, t.net.forward(Xv)));
      for (const OutputQuality& oq : q) score += oq.r2 / static_cast<double>(q.size());
    } else {
      score = -trial.training_mse;
    }
    trial.validation_r2 = Xv.rows() > 0 ? score : std::numeric_limits<double>::quiet_NaN();
    fit.trials.push_back(trial);
    if (options.progress)
      log::info("gabp: hidden " + std::to_string(hidden) + ": validation R^2 " + std::to_string(trial.validation_r2) +
                " after " + std::to_string(t.lm.epochs) + " LM epochs");
    if (score > best_score) {
      best_score = score;
      fit.network = t.net;
      fit.ga_best_mse = t.ga_mse;
      fit.epochs = t.lm.epochs;
      fit.stop_reason = t.lm.stop_reason;
    }
  }
  fit.training = prediction_quality(outputs, rows_of(Y, fit.training_rows), unscale(fit.output_scaling, fit.network.forward(Xt)));
  if (Xv.rows() > 0)
    fit.validation = prediction_quality(outputs, rows_of(Y, fit.validation_rows), unscale(fit.output_scaling, fit.network.forward(Xv)));
  return fit;
}

}  // namespace demcal::surrogate
