#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/doe/space_filling.hpp"

namespace demcal::doe {

LhsCriterion parse_lhs_criterion(const std::string& text) {
  if (text == "random") return LhsCriterion::Random;
  if (text == "center" || text == "centre") return LhsCriterion::Center;
  if (text == "maximin") return LhsCriterion::Maximin;
  if (text == "phip") return LhsCriterion::PhiP;
  throw Error("lhs: --criterion \"" + text + "\": expected random, center, maximin or phip");
}

double phi_p(const Eigen::MatrixXd& points, double p) {
  double sum = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (Eigen::Index j = i + 1; j < points.rows(); ++j)
      sum += std::pow((points.row(i) - points.row(j)).norm(), -p);
  return std::pow(sum, 1.0 / p);
}

double min_distance(const Eigen::MatrixXd& points) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (Eigen::Index j = i + 1; j < points.rows(); ++j) best = std::min(best, (points.row(i) - points.row(j)).norm());
  return best;
}

namespace {

// phi_p bookkeeping for element swaps: keeps the pairwise terms d^-p so a
// swap of two entries in one column costs O(n k) instead of O(n^2 k).
class PhiTracker {
 public:
  PhiTracker(const Eigen::MatrixXd& x, double p) : x_(x), p_(p), n_(x.rows()) {
    terms_ = Eigen::MatrixXd::Zero(n_, n_);
    for (Eigen::Index i = 0; i < n_; ++i)
      for (Eigen::Index j = i + 1; j < n_; ++j) terms_(i, j) = terms_(j, i) = term(i, j, x_);
    sum_ = terms_.sum() / 2.0;
  }
  double phi() const { return std::pow(sum_, 1.0 / p_); }
  const Eigen::MatrixXd& points() const { return x_; }

  // phi_p after swapping x(a, c) and x(b, c), without applying it.
  double phi_after_swap(Eigen::Index a, Eigen::Index b, Eigen::Index c) {
    double sum = sum_;
    std::swap(x_(a, c), x_(b, c));
    for (Eigen::Index j = 0; j < n_; ++j) {
      if (j != a) sum += term(a, j, x_) - terms_(a, j);
      if (j != b && j != a) sum += term(b, j, x_) - terms_(b, j);
    }
    std::swap(x_(a, c), x_(b, c));
    return std::pow(std::max(sum, 0.0), 1.0 / p_);
  }

  void apply_swap(Eigen::Index a, Eigen::Index b, Eigen::Index c) {
    std::swap(x_(a, c), x_(b, c));
    for (Eigen::Index j = 0; j < n_; ++j) {
      if (j != a) {
        double t = term(a, j, x_);
        sum_ += t - terms_(a, j);
        terms_(a, j) = terms_(j, a) = t;
      }
      if (j != b) {
        double t = term(b, j, x_);
        if (j != a) sum_ += t - terms_(b, j);
        terms_(b, j) = terms_(j, b) = t;
      }
    }
  }

 private:
  double term(Eigen::Index i, Eigen::Index j, const Eigen::MatrixXd& x) const {
    return std::pow((x.row(i) - x.row(j)).norm(), -p_);
  }
  Eigen::MatrixXd x_;
  double p_;
  Eigen::Index n_;
  Eigen::MatrixXd terms_;
  double sum_ = 0;
};

Eigen::MatrixXd random_lhs(int runs, int factors, bool centred, Rng& rng) {
  Eigen::MatrixXd x(runs, factors);
  std::vector<int> strata(static_cast<std::size_t>(runs));
  for (int j = 0; j < factors; ++j) {
    for (int i = 0; i < runs; ++i) strata[static_cast<std::size_t>(i)] = i;
    rng.shuffle(strata);
    for (int i = 0; i < runs; ++i) {
      double offset = centred ? 0.5 : rng.uniform();
      x(i, j) = (strata[static_cast<std::size_t>(i)] + offset) / runs;
    }
  }
  return x;
}

// Enhanced stochastic evolutionary algorithm with threshold acceptance.
Eigen::MatrixXd optimise_ese(Eigen::MatrixXd x, double p, int outer_iterations, Rng& rng) {
  const Eigen::Index n = x.rows(), k = x.cols();
  if (n < 3) return x;
  PhiTracker current(x, p);
  Eigen::MatrixXd best = x;
  double best_phi = current.phi();
  const double pairs = static_cast<double>(n) * static_cast<double>(n - 1) / 2.0;
  const int candidates = static_cast<int>(std::max(1.0, std::min(pairs / 5.0, 50.0)));
  const int inner = static_cast<int>(std::max(1.0, std::min(2.0 * pairs * static_cast<double>(k) / candidates, 100.0)));
  double threshold = 0.005 * best_phi;
  bool heating = true;  // exploration: warm up until acceptance is high, then cool

  for (int outer = 0; outer < outer_iterations; ++outer) {
    double start_best = best_phi;
    int accepted = 0, improved = 0;
    for (int i = 0; i < inner; ++i) {
      Eigen::Index column = i % k;
      Eigen::Index try_a = 0, try_b = 0;
      double try_phi = std::numeric_limits<double>::infinity();
      for (int c = 0; c < candidates; ++c) {
        Eigen::Index a = static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n)));
        Eigen::Index b = static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n - 1)));
        if (b >= a) ++b;
        double phi = current.phi_after_swap(a, b, column);
        if (phi < try_phi) {
          try_phi = phi;
          try_a = a;
          try_b = b;
        }
      }
      if (try_phi - current.phi() <= threshold * rng.uniform()) {
        current.apply_swap(try_a, try_b, column);
        ++accepted;
        double phi = current.phi();
        if (phi < best_phi) {
          best_phi = phi;
          best = current.points();
          ++improved;
        }
      }
    }
    double accept_ratio = static_cast<double>(accepted) / inner;
    double improve_ratio = static_cast<double>(improved) / inner;
    if (best_phi < start_best - 1e-12 * start_best) {
      // Improving: tighten while many moves are accepted but few improve.
      if (accept_ratio > 0.1 && improve_ratio < accept_ratio)
        threshold *= 0.8;
      else if (accept_ratio <= 0.1)
        threshold /= 0.8;
    } else {
      // Exploring: heat quickly until 80 % are accepted, then cool slowly to 10 %.
      if (heating && accept_ratio >= 0.8) heating = false;
      if (!heating && accept_ratio <= 0.1) heating = true;
      threshold = heating ? threshold / 0.7 : threshold * 0.9;
    }
  }
  return best;
}

}  // namespace

Design latin_hypercube(const LhsOptions& options) {
  if (options.runs < 2) throw Error("lhs: --runs must be at least 2 (got " + std::to_string(options.runs) + ")");
  if (options.factors < 1) throw Error("lhs: needs at least one factor");
  if (!(options.p > 0)) throw Error("lhs: phi_p exponent must be positive");
  Rng rng(options.seed);
  bool centred = options.criterion == LhsCriterion::Center;
  Eigen::MatrixXd x = random_lhs(options.runs, options.factors, centred, rng);
  std::string name = "random";
  double p = options.p;
  int outer = options.outer_iterations;
  if (outer <= 0) outer = options.runs <= 100 ? 100 : 30;
  if (options.criterion == LhsCriterion::Center) name = "centred";
  if (options.criterion == LhsCriterion::Maximin || options.criterion == LhsCriterion::PhiP) {
    if (options.criterion == LhsCriterion::Maximin) p = 50.0;
    x = optimise_ese(x, p, outer, rng);
    name = options.criterion == LhsCriterion::Maximin ? "maximin (ESE on phi_50)" : "phi_p (ESE, p = " + format_double(p) + ")";
  }
  Design design = make_design("lhs", std::move(x), 0, Coding::Unit);
  design.description = "Latin hypercube, " + name + ", " + std::to_string(options.runs) + " runs";
  design.settings["criterion"] = name;
  design.settings["seed"] = std::to_string(options.seed);
  if (options.criterion == LhsCriterion::Maximin || options.criterion == LhsCriterion::PhiP) {
    design.settings["ese_outer_iterations"] = std::to_string(outer);
    design.settings["phi_p_exponent"] = format_double(p);
  }
  return design;
}

}  // namespace demcal::doe
