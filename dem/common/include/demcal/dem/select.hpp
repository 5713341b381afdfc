#pragma once
// cond ? a : b for the vectorised loops of both engines, bit for bit, as
// masks: with a ?: the optimiser moves the loads only one side needs behind
// a branch, and a loop with a branch does not vectorise.
#include <cstdint>
#include <cstring>

namespace demcal::dem {

inline double select(bool cond, double a, double b) {
  std::uint64_t ua, ub;
  std::memcpy(&ua, &a, sizeof ua);
  std::memcpy(&ub, &b, sizeof ub);
  const std::uint64_t mask = -static_cast<std::uint64_t>(cond);
  const std::uint64_t bits = (ua & mask) | (ub & ~mask);
  double out;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}

}  // namespace demcal::dem
