#pragma once
// Bond strengths drawn per contact from a normal distribution truncated at
// zero (redrawn while negative), as PFC's material genesis does.
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

}  // namespace demcal::dem
