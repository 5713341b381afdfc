#include "demcal/dem/wave_signals.hpp"

#include <cmath>
#include <limits>

namespace demcal::dem {

Recovery recovery_time(const std::vector<double>& t, const std::vector<double>& speed, double threshold) {
  Recovery r;
  std::size_t last = t.size();  // last sample at or above the threshold
  for (std::size_t k = 0; k < t.size(); ++k)
    if (std::abs(speed[k]) >= threshold) last = k;
  if (last == t.size()) return r;
  if (last + 1 == t.size()) {
    r.time_s = t.back();
    r.recovered = false;
    return r;
  }
  const double a = std::abs(speed[last]), b = std::abs(speed[last + 1]);
  r.time_s = t[last] + (a - threshold) / (a - b) * (t[last + 1] - t[last]);
  return r;
}

double first_crossing(const std::vector<double>& t, const std::vector<double>& v, double level) {
  for (std::size_t k = 1; k < t.size(); ++k)
    if (v[k - 1] < level && v[k] >= level) return t[k - 1] + (level - v[k - 1]) / (v[k] - v[k - 1]) * (t[k] - t[k - 1]);
  return std::numeric_limits<double>::quiet_NaN();
}

double arrival_speed(const std::vector<double>& x, const std::vector<double>& arrival_t) {
  double n = 0, st = 0, sx = 0, stt = 0, stx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!std::isfinite(arrival_t[k])) continue;
    n += 1;
    st += arrival_t[k];
    sx += x[k];
    stt += arrival_t[k] * arrival_t[k];
    stx += arrival_t[k] * x[k];
  }
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  return (n * stx - st * sx) / (n * stt - st * st);
}

double signed_extreme(const std::vector<double>& t, const std::vector<double>& v, double from, double to) {
  double best = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= from && t[k] < to && std::abs(v[k]) > std::abs(best)) best = v[k];
  return best;
}

}  // namespace demcal::dem
