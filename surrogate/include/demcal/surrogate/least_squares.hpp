#pragma once
// Ordinary least squares by column-pivoted (rank-revealing) Householder QR.
// Every fit in the analysis stage (ANOVA models, response surfaces, the
// reduced models behind adjusted sums of squares) goes through here.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace demcal::surrogate {

struct LeastSquaresFit {
  Eigen::VectorXd coefficients;   // one per column of X
  Eigen::VectorXd fitted;
  Eigen::VectorXd residuals;
  double sse = 0.0;               // residual sum of squares
  int rank = 0;
  int residual_df = 0;            // rows - rank
  Eigen::MatrixXd unscaled_covariance;  // (X'X)^-1, valid when rank == cols
  Eigen::VectorXd leverage;       // diagonal of the hat matrix
};

// Fits y ~ X. Columns are scaled to unit norm before the QR so that the rank
// decision does not depend on units. When X is rank deficient the fit is still
// returned (rank < cols); callers decide whether that is an error.
LeastSquaresFit least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y);

// Indices of columns that are linear combinations of earlier ones.
std::vector<int> dependent_columns(const Eigen::MatrixXd& X);

// SSE of y ~ X (only the residual sum of squares, for reduced models).
double residual_sum_of_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y);

}  // namespace demcal::surrogate
