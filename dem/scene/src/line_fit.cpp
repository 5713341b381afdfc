#include "demcal/dem/line_fit.hpp"

#include "demcal/core/error.hpp"

namespace demcal::dem {

FittedLine fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::string& too_few,
                    const std::string& no_spread) {
  if (x.size() != y.size() || x.size() < 2) throw Error(too_few);
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
  }
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double dx = x[k] - mx, dy = y[k] - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  if (!(sxx > 0)) throw Error(no_spread);
  FittedLine line;
  line.slope = sxy / sxx;
  line.intercept = my - line.slope * mx;
  line.r2 = syy > 0 ? sxy * sxy / (sxx * syy) : 1.0;
  return line;
}

}  // namespace demcal::dem
