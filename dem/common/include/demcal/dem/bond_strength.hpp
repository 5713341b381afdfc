#pragma once
// Bond strengths drawn per contact from a normal distribution truncated at
// zero (redrawn while negative), as PFC's material genesis does.
#include <cmath>

#include "demcal/core/rng.hpp"

namespace demcal::dem {

inline double draw_strength(double mean, double std_dev, Rng& rng) {
  if (std_dev <= 0) return mean;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    double value = rng.normal(mean, std_dev);
    if (value >= 0) return value;
  }
  return 0.0;  // only when the mean lies many deviations below zero
}

// A load against a strength as the break tests compare them (load >= strength
// breaks): load / strength, and for a strength of 0 (any load >= 0 breaks)
// infinity when loaded, 0 when not.
inline double utilisation(double load, double strength) {
  if (strength > 0) return load / strength;
  return load >= 0 ? INFINITY : 0.0;
}

}  // namespace demcal::dem
