#pragma once
// Global sensitivity of any Model over its domain (inputs uniform on the
// box): variance-based Sobol indices by Saltelli sampling (first order,
// Saltelli 2010; total, Jansen 1999) with bootstrap confidence intervals, and
// Morris elementary effects (mu, mu*, sigma) in unit-cube units.
#include <cstdint>
#include <string>
#include <vector>

#include "demcal/core/model.hpp"

namespace demcal::surrogate {

struct SobolIndices {
  std::string output;
  std::vector<std::string> inputs;
  std::vector<double> first, first_conf, total, total_conf;  // conf: 95 % half-width
  double variance = 0.0;
  int evaluations = 0;
};

// `base_samples` N: N (k + 2) model evaluations on a scrambled Sobol sequence.
std::vector<SobolIndices> sobol_indices(const Model& model, int base_samples, std::uint64_t seed, int bootstrap = 100);

struct MorrisIndices {
  std::string output;
  std::vector<std::string> inputs;
  std::vector<double> mu, mu_star, sigma;
  int evaluations = 0;
};

// `trajectories` r: r (k + 1) evaluations on a `levels`-level grid (even).
std::vector<MorrisIndices> morris_indices(const Model& model, int trajectories, std::uint64_t seed, int levels = 4);

}  // namespace demcal::surrogate
