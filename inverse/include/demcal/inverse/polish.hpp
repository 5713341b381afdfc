#pragma once
// Local polish of a point by bounded nonlinear least squares on the relative
// residuals (y_i - t_i) / |t_i| (Ceres, trust region, numeric derivatives
// scaled to each parameter's bound width).
#include "demcal/inverse/problem.hpp"

namespace demcal::inverse {

struct PolishResult {
  Point x;
  long evaluations = 0;
  std::string summary;  // Ceres' one-line report
};

PolishResult polish(const InversionProblem& problem, const Point& start, int max_iterations = 200);

}  // namespace demcal::inverse
