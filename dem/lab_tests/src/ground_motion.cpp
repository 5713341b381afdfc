// An earthquake record integrated into an input velocity (ground_motion.hpp).
#include "demcal/dem/ground_motion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem {

double GroundMotion::velocity_at(double t_s) const {
  if (velocity_m_s.empty() || t_s <= 0) return 0.0;
  const double position = t_s / dt_s;
  const std::size_t k = static_cast<std::size_t>(position);
  if (k + 1 >= velocity_m_s.size()) return 0.0;  // the record is over; it ends at rest
  const double f = position - static_cast<double>(k);
  return velocity_m_s[k] + f * (velocity_m_s[k + 1] - velocity_m_s[k]);
}

double GroundMotion::peak_speed_m_s() const {
  double peak = 0;
  for (double v : velocity_m_s) peak = std::max(peak, std::abs(v));
  return peak;
}

double GroundMotion::peak_acceleration_m_s2() const {
  double peak = 0;
  for (double a : acceleration_m_s2) peak = std::max(peak, std::abs(a));
  return peak;
}

std::vector<double> read_acceleration_record(const std::string& path, RecordFormat format, double& time_step_s,
                                             const std::string& where) {
  std::ifstream in(path);
  if (!in) throw Error(where + ".record_file: cannot read " + path);
  std::vector<double> values, times;
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream tokens(line);
    std::string token;
    std::vector<double> numbers;
    while (tokens >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v))
        throw Error(path + ": line " + std::to_string(line_number) + ": \"" + token + "\" is not a number");
      numbers.push_back(v);
    }
    if (format == RecordFormat::values) {
      values.insert(values.end(), numbers.begin(), numbers.end());
      continue;
    }
    if (numbers.size() != 2)
      throw Error(path + ": line " + std::to_string(line_number) + ": a time_value record has two numbers per line " +
                  "(time, acceleration), found " + std::to_string(numbers.size()));
    times.push_back(numbers[0]);
    values.push_back(numbers[1]);
    const std::size_t n = times.size();
    if (n >= 3) {
      const double step = times[n - 1] - times[n - 2], first_step = times[1] - times[0];
      if (!(std::abs(step - first_step) <= 1e-6 * std::abs(first_step) + 1e-12))
        throw Error(path + ": line " + std::to_string(line_number) + ": uneven time step (" + format_double(step) +
                    " s after " + format_double(first_step) + " s at the start); the record must be evenly sampled");
    }
  }
  if (values.size() < 2) throw Error(path + ": fewer than 2 accelerations");
  if (format == RecordFormat::time_value) {
    const double step = times[1] - times[0];
    if (!(step > 0)) throw Error(path + ": the times must increase");
    if (time_step_s > 0 && std::abs(time_step_s - step) > 1e-6 * step)
      throw Error(where + ".time_step_s " + format_double(time_step_s) + " s differs from the record's own, " +
                  format_double(step) + " s");
    time_step_s = step;
  }
  if (!(time_step_s > 0)) throw Error(where + ".time_step_s: missing (the record lists values only)");
  return values;
}

GroundMotion ground_motion(const std::vector<double>& acceleration, double time_step_s, double scale_to_m_s2,
                           double duration_s, Baseline baseline) {
  GroundMotion g;
  g.dt_s = time_step_s;
  std::size_t n = acceleration.size();
  if (duration_s > 0) n = std::min(n, static_cast<std::size_t>(std::floor(duration_s / time_step_s + 1e-9)) + 1);
  g.acceleration_m_s2.resize(n);
  for (std::size_t k = 0; k < n; ++k) g.acceleration_m_s2[k] = acceleration[k] * scale_to_m_s2;
  auto integrate = [&] {
    g.velocity_m_s.assign(n, 0.0);
    for (std::size_t k = 1; k < n; ++k)
      g.velocity_m_s[k] = g.velocity_m_s[k - 1] + 0.5 * time_step_s * (g.acceleration_m_s2[k - 1] + g.acceleration_m_s2[k]);
  };
  integrate();
  if (baseline == Baseline::end_at_rest && n > 1) {
    g.baseline_offset_m_s2 = g.velocity_m_s.back() / g.duration_s();
    for (double& a : g.acceleration_m_s2) a -= g.baseline_offset_m_s2;
    integrate();
  }
  return g;
}

}  // namespace demcal::dem
