#include "demcal/dem/thread_balance.hpp"

#include <algorithm>

namespace demcal::dem {

namespace {
constexpr double kTolerance = 0.03;  // slowest over fastest, above which the cuts move
constexpr double kSmallestShareOfEqual = 0.25;
}  // namespace

std::vector<double> equal_cuts(std::size_t team) {
  std::vector<double> cuts(team + 1);
  for (std::size_t t = 0; t <= team; ++t) cuts[t] = static_cast<double>(t) / static_cast<double>(team);
  return cuts;
}

bool rebalance_cuts(std::vector<double>& cuts, const std::vector<double>& busy_s) {
  const std::size_t team = busy_s.size();
  if (team < 2 || cuts.size() != team + 1) return false;
  const auto [fastest, slowest] = std::minmax_element(busy_s.begin(), busy_s.end());
  if (!(*fastest > 0) || *slowest <= *fastest * (1 + kTolerance)) return false;

  // Each thread's rate (its share per second); at widths in proportion to
  // the rates all would take the same time. Halfway there, the widths still
  // add up to 1.
  double rate_sum = 0;
  for (std::size_t t = 0; t < team; ++t) rate_sum += (cuts[t + 1] - cuts[t]) / busy_s[t];
  std::vector<double> width(team);
  for (std::size_t t = 0; t < team; ++t) {
    const double now = cuts[t + 1] - cuts[t];
    width[t] = 0.5 * (now + now / busy_s[t] / rate_sum);
  }
  // Parts that would fall below the smallest share are held at it, the
  // others shrunk in proportion (which may bring another down to it: until
  // none does).
  const double smallest = kSmallestShareOfEqual / static_cast<double>(team);
  std::vector<char> held(team, 0);
  double scale = 1;
  for (bool changed = true; changed;) {
    double held_sum = 0, free_sum = 0;
    for (std::size_t t = 0; t < team; ++t) {
      if (held[t])
        held_sum += smallest;
      else
        free_sum += width[t];
    }
    scale = (1 - held_sum) / free_sum;
    changed = false;
    for (std::size_t t = 0; t < team; ++t)
      if (!held[t] && width[t] * scale < smallest) held[t] = changed = true;
  }
  for (std::size_t t = 0; t + 1 < team; ++t) cuts[t + 1] = cuts[t] + (held[t] ? smallest : width[t] * scale);
  cuts[team] = 1.0;
  return true;
}

}  // namespace demcal::dem
