#pragma once
// Space-filling designs on the unit cube: Latin hypercubes (random, centred,
// optimised) and scrambled Sobol points, with their distance criteria.
#include <cstdint>
#include <string>

#include "demcal/doe/design.hpp"

namespace demcal::doe {

enum class LhsCriterion { Random, Center, Maximin, PhiP };
LhsCriterion parse_lhs_criterion(const std::string& text);

struct LhsOptions {
  int runs = 0;
  int factors = 0;
  LhsCriterion criterion = LhsCriterion::Random;
  std::uint64_t seed = 1;
  int outer_iterations = 0;  // ESE outer loops; 0 picks a default by size
  double p = 10.0;           // exponent of phi_p for the phip criterion
};

// Each column has exactly one point in each of the `runs` strata of [0, 1).
// Random: uniform inside the stratum; Center: at its midpoint. Maximin and
// PhiP start from a random LHS and improve it with the enhanced stochastic
// evolutionary algorithm (Jin, Chen & Sudjianto 2005) by swapping values
// within a column (so the Latin property holds throughout), minimising phi_p
// (p = 10 for PhiP; p = 50 for Maximin, where phi_p orders designs as the
// smallest pairwise distance does).
Design latin_hypercube(const LhsOptions& options);

// Owen-scrambled Sobol points (Boost.Random's Sobol engine, Joe-Kuo
// direction numbers, hash-based nested uniform scrambling per dimension).
Design sobol(int runs, int factors, std::uint64_t seed);

// Morris-Mitchell phi_p = (sum_{i<j} d_ij^-p)^(1/p), Euclidean distances
// between rows (smaller is better).
double phi_p(const Eigen::MatrixXd& points, double p);
// Smallest Euclidean distance between two rows.
double min_distance(const Eigen::MatrixXd& points);

}  // namespace demcal::doe
