#include "demcal/inverse/polish.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

namespace demcal::inverse {

namespace {

// Works in unit coordinates u in [0, 1] per parameter so that one numeric
// step size suits parameters of any magnitude.
struct RelativeResiduals {
  const InversionProblem* problem;
  long* evaluations;

  bool operator()(double const* const* parameters, double* residuals) const {
    const Bounds& b = problem->bounds();
    Point x(b.size());
    for (std::size_t j = 0; j < x.size(); ++j) x[j] = b.low[j] + parameters[0][j] * (b.high[j] - b.low[j]);
    std::vector<double> y = problem->predict_targets(x);
    const std::vector<Target>& t = problem->targets();
    ++*evaluations;
    for (std::size_t i = 0; i < t.size(); ++i) {
      residuals[i] = (y[i] - t[i].value) / std::fabs(t[i].value);
      if (!std::isfinite(residuals[i])) return false;
    }
    return true;
  }
};

}  // namespace

PolishResult polish(const InversionProblem& problem, const Point& start, int max_iterations) {
  const Bounds& b = problem.bounds();
  const int n = static_cast<int>(b.size());
  PolishResult result;
  std::vector<double> u(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    u[static_cast<std::size_t>(j)] = std::clamp((start[static_cast<std::size_t>(j)] - b.low[static_cast<std::size_t>(j)]) /
                                                    (b.high[static_cast<std::size_t>(j)] - b.low[static_cast<std::size_t>(j)]),
                                                0.0, 1.0);
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = 1e-7;
  auto* cost = new ceres::DynamicNumericDiffCostFunction<RelativeResiduals, ceres::CENTRAL>(
      new RelativeResiduals{&problem, &result.evaluations}, ceres::TAKE_OWNERSHIP, diff);
  cost->AddParameterBlock(n);
  cost->SetNumResiduals(static_cast<int>(problem.targets().size()));
  ceres::Problem ls;
  ls.AddResidualBlock(cost, nullptr, u.data());
  for (int j = 0; j < n; ++j) {
    ls.SetParameterLowerBound(u.data(), j, 0.0);
    ls.SetParameterUpperBound(u.data(), j, 1.0);
  }
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-15;
  options.parameter_tolerance = 1e-14;
  options.gradient_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ls, &summary);
  result.summary = summary.BriefReport();
  result.x.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    auto k = static_cast<std::size_t>(j);
    result.x[k] = std::clamp(b.low[k] + u[k] * (b.high[k] - b.low[k]), b.low[k], b.high[k]);
  }
  return result;
}

}  // namespace demcal::inverse
