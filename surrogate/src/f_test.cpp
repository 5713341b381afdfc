#include "demcal/surrogate/f_test.hpp"

#include <cmath>
#include <limits>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace demcal::surrogate {

double f_upper_tail(double f, double df1, double df2) {
  if (!(df1 > 0) || !(df2 > 0) || std::isnan(f)) return std::numeric_limits<double>::quiet_NaN();
  if (f <= 0) return 1.0;
  if (std::isinf(f)) return 0.0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f(df1, df2), f));
}

double f_critical(double alpha, double df1, double df2) {
  if (!(df1 > 0) || !(df2 > 0) || !(alpha > 0 && alpha < 1)) return std::numeric_limits<double>::quiet_NaN();
  return boost::math::quantile(boost::math::complement(boost::math::fisher_f(df1, df2), alpha));
}

double t_two_sided(double t, double df) {
  if (!(df > 0) || std::isnan(t)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return 0.0;
  return 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(df), std::fabs(t)));
}

std::string significance_mark(double p) {
  if (std::isnan(p)) return "";
  if (p < 0.01) return "**";
  if (p < 0.05) return "*";
  return "";
}

}  // namespace demcal::surrogate
