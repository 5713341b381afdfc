#pragma once
// Linear and full quadratic response surfaces fitted by least squares:
//   y = b0 + sum b_j x_j [+ sum b_jj x_j^2 + sum_{i<j} b_ij x_i x_j]
// The fit, its ANOVA and its coded coefficients are computed in coded units
// x = (X - center) / half_range, as Minitab does; the coefficients are also
// given in natural units (the model file predicts with those).
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demcal/core/model.hpp"
#include "demcal/surrogate/anova_table.hpp"

namespace demcal::surrogate {

enum class SurfaceKind { Linear, Quadratic };
std::string to_string(SurfaceKind kind);

enum class TermGroup { Constant, Linear, Square, Interaction };

struct SurfaceTerm {
  std::string name;          // "1", "A", "A^2", "A*B"
  std::vector<int> factors;  // {}, {i}, {i, i}, {i, j}
  TermGroup group = TermGroup::Constant;
};

// Every term of the surface in Minitab's order: constant, linear, squares, interactions.
std::vector<SurfaceTerm> surface_terms(const std::vector<std::string>& factors, SurfaceKind kind);
double term_value(const SurfaceTerm& term, const double* x);

struct FactorCoding {
  double center = 0.0;
  double half_range = 1.0;
};

struct SurfaceOptions {
  SurfaceKind kind = SurfaceKind::Quadratic;
  // Coded -1/+1 points per factor; empty: the data's min and max (a space file
  // gives the CCD cube's low/high instead, as Minitab codes it).
  std::vector<FactorCoding> coding;
  // Backward elimination at this alpha keeping hierarchy; 0: keep every term.
  double eliminate_alpha = 0.0;
};

struct CoefficientRow {
  std::string term;
  double coef = 0.0;
  double se = 0.0;
  double t = 0.0;
  double p = 0.0;
  double vif = std::numeric_limits<double>::quiet_NaN();  // coded table only, not for the constant
};

struct SurfaceFit {
  std::string response;
  SurfaceKind kind = SurfaceKind::Quadratic;
  std::vector<std::string> factors;
  std::vector<FactorCoding> coding;
  std::vector<InputRange> domain;      // data min/max of each factor
  std::vector<SurfaceTerm> terms;      // the terms kept
  std::vector<std::string> eliminated; // in the order they left
  std::vector<CoefficientRow> coded;
  std::vector<CoefficientRow> natural;
  int runs = 0;
  int distinct_points = 0;
  double mean_response = 0.0;
  double s = 0.0;        // sqrt(MSE)
  double r2 = 0.0;
  double r2_adj = 0.0;
  double r2_pred = 0.0;  // 1 - PRESS/SST (may be negative; Minitab prints 0 then)
  double press = 0.0;
  std::vector<AnovaRow> anova;  // Model, groups and terms, Error, Lack-of-Fit, Pure Error, Total
  std::string note;             // why a usual part of the table is missing, if one is
  Eigen::VectorXd observed, fitted, press_residuals;
  // (Z'Z)^-1 of the kept terms in coded units and the error's degrees of
  // freedom: with s, the prediction interval of a new run anywhere.
  Eigen::MatrixXd coded_covariance_unscaled;
  int error_df = 0;
};

// X: runs x factors in natural units. Errors name what is wrong: constant
// columns, too few runs (and how many are needed), terms the design cannot
// estimate.
SurfaceFit fit_surface(const std::vector<std::string>& factors, const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                       const std::string& response, const SurfaceOptions& options);

// Prediction from the natural coefficients; x in factor order.
double predict_surface(const SurfaceFit& fit, const double* x);

}  // namespace demcal::surrogate
