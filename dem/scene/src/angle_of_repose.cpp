#include "demcal/dem/angle_of_repose.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "demcal/core/error.hpp"
#include "demcal/dem/line_fit.hpp"

namespace demcal::dem {
SurfaceProfile surface_profile(const std::vector<double>& x_m, const std::vector<double>& y_m,
                               const std::vector<double>& radius_m, double base_y_m, double bin_width_m) {
  if (!(bin_width_m > 0)) throw Error("angle of repose: the bin width must be positive");
  if (x_m.empty()) throw Error("angle of repose: no particles on the base");
  double lo = x_m[0] - radius_m[0], hi = x_m[0] + radius_m[0];
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    lo = std::min(lo, x_m[i] - radius_m[i]);
    hi = std::max(hi, x_m[i] + radius_m[i]);
  }
  const std::size_t bins = static_cast<std::size_t>(std::ceil((hi - lo) / bin_width_m)) + 1;
  // Each bin's highest particle top; a disk counts in the bin of its centre.
  std::vector<double> top(bins, -1.0);
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const auto b = static_cast<std::size_t>((x_m[i] - lo) / bin_width_m);
    top[b] = std::max(top[b], y_m[i] + radius_m[i] - base_y_m);
  }
  SurfaceProfile profile;
  for (std::size_t b = 0; b < bins; ++b) {
    if (top[b] < 0) continue;
    if (profile.x_m.empty() || top[b] > profile.height_m[profile.highest]) profile.highest = profile.x_m.size();
    profile.x_m.push_back(lo + (b + 0.5) * bin_width_m);
    profile.height_m.push_back(top[b]);
  }
  return profile;
}

namespace {
void check_fractions(const ReposeOptions& options) {
  if (!(options.low_fraction >= 0 && options.low_fraction < options.high_fraction && options.high_fraction <= 1))
    throw Error("angle of repose: the flank's height fractions must satisfy 0 <= low < high <= 1");
}
}  // namespace

SlopeFit fit_slope(const SurfaceProfile& profile, const ReposeOptions& options, const std::string& what) {
  check_fractions(options);
  if (profile.x_m.empty()) throw Error(what + ": no surface points");
  const double top = profile.height_m[profile.highest];
  const double low = options.low_fraction * top, high = options.high_fraction * top;
  std::vector<double> x, h;
  for (std::size_t k = 0; k < profile.x_m.size(); ++k)
    if (profile.height_m[k] >= low && profile.height_m[k] <= high) {
      x.push_back(profile.x_m[k]);
      h.push_back(profile.height_m[k]);
    }
  SlopeFit fit;
  fit.points = x.size();
  if (x.size() < std::max<std::size_t>(2, options.min_points))
    throw Error(what + ": " + std::to_string(x.size()) + " surface points between " +
                std::to_string(static_cast<int>(100 * options.low_fraction)) + " and " +
                std::to_string(static_cast<int>(100 * options.high_fraction)) + " % of its height (at least " +
                std::to_string(options.min_points) + " needed): the slope is too short for the bin width");
  const FittedLine line = fit_line(x, h, what + ": too few slope points", what + ": the slope's points share one x");
  fit.deg = std::atan(std::abs(line.slope)) * 180.0 / M_PI;
  fit.slope = line.slope;
  fit.intercept_m = line.intercept;
  fit.r2 = line.r2;
  return fit;
}

ReposeFit fit_angle_of_repose(const std::vector<double>& x_m, const std::vector<double>& y_m,
                              const std::vector<double>& radius_m, double base_y_m, const ReposeOptions& options) {
  if (!(options.bin_width_m > 0)) throw Error("angle of repose: the bin width must be positive");
  check_fractions(options);
  const SurfaceProfile profile = surface_profile(x_m, y_m, radius_m, base_y_m, options.bin_width_m);
  ReposeFit fit;
  fit.profile_x_m = profile.x_m;
  fit.profile_height_m = profile.height_m;
  fit.height_m = profile.height_m[profile.highest];
  fit.apex_x_m = profile.x_m[profile.highest];
  const double low = options.low_fraction * fit.height_m, high = options.high_fraction * fit.height_m;
  std::vector<double> lx, ly, rx, ry;
  for (std::size_t k = 0; k < fit.profile_x_m.size(); ++k) {
    const double h = fit.profile_height_m[k], x = fit.profile_x_m[k];
    if (h < low || h > high) continue;
    if (x < fit.apex_x_m) {
      lx.push_back(x);
      ly.push_back(h);
    } else if (x > fit.apex_x_m) {
      rx.push_back(x);
      ry.push_back(h);
    }
  }
  fit.left_points = lx.size();
  fit.right_points = rx.size();
  if (lx.size() < options.min_points || rx.size() < options.min_points)
    throw Error("angle of repose: the heap's flanks have " + std::to_string(lx.size()) + " and " +
                std::to_string(rx.size()) + " surface points between " +
                std::to_string(static_cast<int>(100 * options.low_fraction)) + " and " +
                std::to_string(static_cast<int>(100 * options.high_fraction)) + " % of its height (at least " +
                std::to_string(options.min_points) + " each needed): the heap is too low for the bin width");
  // Three or more bins per flank, each at its own x: neither message can arise.
  const FittedLine left = fit_line(lx, ly, "angle of repose: too few flank points", "angle of repose: a flank's points share one x"),
                   right = fit_line(rx, ry, "angle of repose: too few flank points", "angle of repose: a flank's points share one x");
  fit.left_deg = std::atan(std::abs(left.slope)) * 180.0 / M_PI;
  fit.right_deg = std::atan(std::abs(right.slope)) * 180.0 / M_PI;
  fit.mean_deg = 0.5 * (fit.left_deg + fit.right_deg);
  fit.left_r2 = left.r2;
  fit.right_r2 = right.r2;
  fit.left_slope = left.slope;
  fit.left_intercept_m = left.intercept;
  fit.right_slope = right.slope;
  fit.right_intercept_m = right.intercept;
  return fit;
}

}  // namespace demcal::dem
