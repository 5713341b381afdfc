#include "demcal/surrogate/least_squares.hpp"

namespace demcal::surrogate {

namespace {

// Relative threshold on the R diagonal below which a column counts as dependent.
constexpr double kRankTolerance = 1e-10;

Eigen::VectorXd column_norms(const Eigen::MatrixXd& X) {
  Eigen::VectorXd norms = X.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < norms.size(); ++j)
    if (norms(j) == 0.0) norms(j) = 1.0;
  return norms;
}

}  // namespace

LeastSquaresFit least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y) {
  const Eigen::Index n = X.rows(), p = X.cols();
  Eigen::VectorXd norms = column_norms(X);
  Eigen::MatrixXd scaled = X * norms.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  qr.setThreshold(kRankTolerance);

  LeastSquaresFit fit;
  fit.rank = static_cast<int>(qr.rank());
  fit.residual_df = static_cast<int>(n) - fit.rank;
  fit.coefficients = qr.solve(y).cwiseQuotient(norms);
  fit.fitted = X * fit.coefficients;
  fit.residuals = y - fit.fitted;
  fit.sse = fit.residuals.squaredNorm();

  if (fit.rank == p) {
    // (X'X)^-1 = S^-1 P R^-1 R^-T P' S^-1 for scaled = Q R P'.
    Eigen::MatrixXd R = qr.matrixR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
    Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
    Eigen::MatrixXd inner = Rinv * Rinv.transpose();
    Eigen::MatrixXd permuted = qr.colsPermutation() * inner * qr.colsPermutation().transpose();
    fit.unscaled_covariance = norms.cwiseInverse().asDiagonal() * permuted * norms.cwiseInverse().asDiagonal();
    // h_ii = || row_i(Q1) ||^2 with Q1 the first p columns of Q.
    Eigen::MatrixXd Q1 = qr.householderQ() * Eigen::MatrixXd::Identity(n, p);
    fit.leverage = Q1.rowwise().squaredNorm();
  }
  return fit;
}

std::vector<int> dependent_columns(const Eigen::MatrixXd& X) {
  std::vector<int> dependent;
  Eigen::VectorXd norms = column_norms(X);
  Eigen::MatrixXd scaled = X * norms.cwiseInverse().asDiagonal();
  // Add columns one at a time: a column that does not raise the rank depends on earlier ones.
  int rank = 0;
  for (Eigen::Index j = 0; j < scaled.cols(); ++j) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled.leftCols(j + 1));
    qr.setThreshold(kRankTolerance);
    if (qr.rank() > rank)
      rank = static_cast<int>(qr.rank());
    else
      dependent.push_back(static_cast<int>(j));
  }
  return dependent;
}

double residual_sum_of_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y) {
  if (X.cols() == 0) return y.squaredNorm();
  Eigen::VectorXd norms = column_norms(X);
  Eigen::MatrixXd scaled = X * norms.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  qr.setThreshold(kRankTolerance);
  return (y - scaled * qr.solve(y)).squaredNorm();
}

}  // namespace demcal::surrogate
