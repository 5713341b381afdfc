#include "demcal/surrogate/response_surface.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "demcal/core/error.hpp"
#include "demcal/surrogate/data_columns.hpp"
#include "demcal/surrogate/f_test.hpp"
#include "demcal/surrogate/least_squares.hpp"

namespace demcal::surrogate {

std::string to_string(SurfaceKind kind) { return kind == SurfaceKind::Linear ? "linear" : "quadratic"; }

std::vector<SurfaceTerm> surface_terms(const std::vector<std::string>& factors, SurfaceKind kind) {
  std::vector<SurfaceTerm> terms{{"1", {}, TermGroup::Constant}};
  const int k = static_cast<int>(factors.size());
  for (int i = 0; i < k; ++i) terms.push_back({factors[i], {i}, TermGroup::Linear});
  if (kind == SurfaceKind::Linear) return terms;
  for (int i = 0; i < k; ++i) terms.push_back({factors[i] + "^2", {i, i}, TermGroup::Square});
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j) terms.push_back({factors[i] + "*" + factors[j], {i, j}, TermGroup::Interaction});
  return terms;
}

double term_value(const SurfaceTerm& term, const double* x) {
  double v = 1.0;
  for (int f : term.factors) v *= x[f];
  return v;
}

namespace {

Eigen::MatrixXd term_matrix(const std::vector<SurfaceTerm>& terms, const Eigen::MatrixXd& X) {
  Eigen::MatrixXd M(X.rows(), static_cast<Eigen::Index>(terms.size()));
  std::vector<double> row(static_cast<std::size_t>(X.cols()));
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (Eigen::Index j = 0; j < X.cols(); ++j) row[static_cast<std::size_t>(j)] = X(i, j);
    for (std::size_t t = 0; t < terms.size(); ++t) M(i, static_cast<Eigen::Index>(t)) = term_value(terms[t], row.data());
  }
  return M;
}

// Columns of M without those whose index is in `drop`.
Eigen::MatrixXd without(const Eigen::MatrixXd& M, const std::vector<int>& drop) {
  Eigen::MatrixXd reduced(M.rows(), M.cols() - static_cast<Eigen::Index>(drop.size()));
  Eigen::Index at = 0;
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    if (std::find(drop.begin(), drop.end(), static_cast<int>(j)) == drop.end()) reduced.col(at++) = M.col(j);
  return reduced;
}

std::vector<CoefficientRow> coefficient_table(const std::vector<SurfaceTerm>& terms, const LeastSquaresFit& fit,
                                              double mse) {
  std::vector<CoefficientRow> rows;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    auto j = static_cast<Eigen::Index>(t);
    CoefficientRow row;
    row.term = terms[t].name;
    row.coef = fit.coefficients(j);
    row.se = std::sqrt(mse * fit.unscaled_covariance(j, j));
    row.t = row.coef / row.se;
    row.p = t_two_sided(row.t, fit.residual_df);
    rows.push_back(row);
  }
  return rows;
}

void require_estimable(const std::vector<SurfaceTerm>& terms, const Eigen::MatrixXd& M, const LeastSquaresFit& fit) {
  if (fit.rank == M.cols()) return;
  std::vector<int> dependent = dependent_columns(M);
  std::string list;
  for (int d : dependent) list += (list.empty() ? "" : ", ") + terms[static_cast<std::size_t>(d)].name;
  throw Error("fit: the design cannot estimate term(s) " + list +
              " (linear combinations of other terms); use a design with more levels or a smaller model");
}

// A term that hierarchy protects: some other kept term contains its factor.
bool protected_by_hierarchy(const SurfaceTerm& term, const std::vector<SurfaceTerm>& terms) {
  if (term.group != TermGroup::Linear) return false;
  for (const SurfaceTerm& other : terms)
    if (other.factors.size() == 2 &&
        std::find(other.factors.begin(), other.factors.end(), term.factors[0]) != other.factors.end())
      return true;
  return false;
}

}  // namespace

SurfaceFit fit_surface(const std::vector<std::string>& factors, const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                       const std::string& response, const SurfaceOptions& options) {
  const Eigen::Index n = X.rows();
  const int k = static_cast<int>(factors.size());
  if (k == 0) throw Error("fit: no factors (--x) given");
  if (n == 0 || y.size() != n) throw Error("fit: the data has no runs");
  require_varying(X, factors, "fit", "a response surface needs every factor to vary");
  if (y.size() > 0 && y.maxCoeff() == y.minCoeff())
    throw Error("fit: response " + response + " is constant; there is nothing to fit");

  SurfaceFit result;
  result.response = response;
  result.kind = options.kind;
  result.factors = factors;
  result.runs = static_cast<int>(n);
  result.mean_response = y.mean();
  for (int j = 0; j < k; ++j) {
    double lo = X.col(j).minCoeff(), hi = X.col(j).maxCoeff();
    result.domain.push_back({factors[j], lo, hi});
    result.coding.push_back({0.5 * (lo + hi), 0.5 * (hi - lo)});
  }
  if (!options.coding.empty()) {
    if (static_cast<int>(options.coding.size()) != k) throw Error("fit: coding given for a different number of factors");
    result.coding = options.coding;
  }
  Eigen::MatrixXd Z(n, k);
  for (int j = 0; j < k; ++j)
    Z.col(j) = (X.col(j).array() - result.coding[j].center) / result.coding[j].half_range;

  std::vector<SurfaceTerm> terms = surface_terms(factors, options.kind);
  const auto p_full = static_cast<Eigen::Index>(terms.size());
  if (n < p_full + 1)
    throw Error("fit: a " + to_string(options.kind) + " surface in " + std::to_string(k) + " factors has " +
                std::to_string(p_full) + " terms and needs at least " + std::to_string(p_full + 1) +
                " runs (one more for the error); the data has " + std::to_string(n));

  Eigen::MatrixXd M;
  LeastSquaresFit fit;
  double mse = 0.0;
  for (;;) {
    M = term_matrix(terms, Z);
    fit = least_squares(M, y);
    require_estimable(terms, M, fit);
    mse = fit.sse / fit.residual_df;
    if (options.eliminate_alpha <= 0) break;
    std::vector<CoefficientRow> rows = coefficient_table(terms, fit, mse);
    int weakest = -1;
    double weakest_p = options.eliminate_alpha;
    for (std::size_t t = 1; t < terms.size(); ++t) {
      if (protected_by_hierarchy(terms[t], terms)) continue;
      if (rows[t].p > weakest_p) {
        weakest_p = rows[t].p;
        weakest = static_cast<int>(t);
      }
    }
    if (weakest < 0 || terms.size() <= 2) break;
    result.eliminated.push_back(terms[static_cast<std::size_t>(weakest)].name);
    terms.erase(terms.begin() + weakest);
  }
  result.terms = terms;
  result.coded_covariance_unscaled = fit.unscaled_covariance;
  result.error_df = fit.residual_df;
  const int p = static_cast<int>(terms.size());

  double sst = (y.array() - y.mean()).square().sum();
  result.s = std::sqrt(mse);
  result.r2 = 1.0 - fit.sse / sst;
  result.r2_adj = 1.0 - (fit.sse / (n - p)) / (sst / (n - 1));
  result.press_residuals = fit.residuals.array() / (1.0 - fit.leverage.array());
  for (Eigen::Index i = 0; i < n; ++i)
    if (fit.leverage(i) > 1.0 - 1e-12) result.press_residuals(i) = std::numeric_limits<double>::infinity();
  result.press = result.press_residuals.squaredNorm();
  result.r2_pred = 1.0 - result.press / sst;
  result.observed = y;
  result.fitted = fit.fitted;
  result.coded = coefficient_table(terms, fit, mse);
  // Variance inflation factors (Minitab prints them beside the coded coefficients):
  // VIF_j = [(X'X)^-1]_jj * sum_i (x_ij - mean_j)^2.
  for (std::size_t t = 1; t < terms.size(); ++t) {
    const auto j = static_cast<Eigen::Index>(t);
    const double centred = (M.col(j).array() - M.col(j).mean()).square().sum();
    result.coded[t].vif = fit.unscaled_covariance(j, j) * centred;
  }

  // Natural units: the same (hierarchical) term set spans the same functions.
  LeastSquaresFit natural = least_squares(term_matrix(terms, X), y);
  result.natural = coefficient_table(terms, natural, natural.sse / natural.residual_df);

  // ANOVA with adjusted sums of squares, laid out as Minitab prints it.
  AnovaRow error{"Error", fit.sse, fit.residual_df};
  error.ms = mse;
  auto adjusted = [&](const std::vector<int>& drop) {
    return std::max(0.0, residual_sum_of_squares(without(M, drop), y) - fit.sse);
  };
  std::vector<AnovaRow> rows;
  std::vector<int> all_but_constant;
  for (int t = 1; t < p; ++t) all_but_constant.push_back(t);
  AnovaRow model{"Model", sst - fit.sse, p - 1};
  complete_row(model, error);
  rows.push_back(model);
  const std::pair<TermGroup, const char*> groups[] = {
      {TermGroup::Linear, "Linear"}, {TermGroup::Square, "Square"}, {TermGroup::Interaction, "2-Way Interaction"}};
  for (auto [group, label] : groups) {
    std::vector<int> members;
    for (int t = 1; t < p; ++t)
      if (terms[static_cast<std::size_t>(t)].group == group) members.push_back(t);
    if (members.empty()) continue;
    AnovaRow g{label, adjusted(members), static_cast<int>(members.size())};
    g.indent = 1;
    complete_row(g, error);
    rows.push_back(g);
    for (int t : members) {
      AnovaRow r{terms[static_cast<std::size_t>(t)].name, adjusted({t}), 1};
      r.indent = 2;
      complete_row(r, error);
      rows.push_back(r);
    }
  }
  rows.push_back(error);

  // Replicated points give pure error; the rest of the residual is lack of fit.
  std::map<std::vector<double>, std::vector<Eigen::Index>> points;
  for (Eigen::Index i = 0; i < n; ++i) {
    std::vector<double> key(X.row(i).data(), X.row(i).data() + 0);
    for (int j = 0; j < k; ++j) key.push_back(X(i, j));
    points[key].push_back(i);
  }
  result.distinct_points = static_cast<int>(points.size());
  const int pure_df = static_cast<int>(n) - result.distinct_points;
  const int lof_df = result.distinct_points - p;
  if (pure_df > 0 && lof_df > 0) {
    double pure_ss = 0.0;
    for (const auto& entry : points) {
      double mean = 0.0;
      for (Eigen::Index i : entry.second) mean += y(i);
      mean /= static_cast<double>(entry.second.size());
      for (Eigen::Index i : entry.second) pure_ss += (y(i) - mean) * (y(i) - mean);
    }
    if (pure_ss <= 1e-12 * sst) {
      // Deterministic runs (same seed at a replicated point) repeat exactly:
      // there is no pure error to test the lack of fit against.
      result.note = "replicated points have identical responses (deterministic runs with the same seed): "
                    "no pure error, lack of fit not tested; run several seeds per point for a replicate error";
    } else {
      AnovaRow pure{"Pure Error", pure_ss, pure_df};
      pure.ms = pure_ss / pure_df;
      pure.indent = 1;
      AnovaRow lof{"Lack-of-Fit", std::max(0.0, fit.sse - pure_ss), lof_df};
      lof.indent = 1;
      complete_row(lof, pure);
      rows.push_back(lof);
      rows.push_back(pure);
    }
  }
  rows.push_back(AnovaRow{"Total", sst, static_cast<int>(n) - 1});
  result.anova = rows;
  return result;
}

double predict_surface(const SurfaceFit& fit, const double* x) {
  double y = 0.0;
  for (std::size_t t = 0; t < fit.terms.size(); ++t) y += fit.natural[t].coef * term_value(fit.terms[t], x);
  return y;
}

}  // namespace demcal::surrogate
