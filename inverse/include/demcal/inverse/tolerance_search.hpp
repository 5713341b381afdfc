#pragma once
// Tolerance search with mean-shift clustering (He et al. 2019): predict many
// Latin-hypercube points, keep those within a relative tolerance of every
// target, cluster the kept points (normalised to the unit box) by mean shift;
// each cluster centre is a candidate parameter set.
#include <cstdint>
#include <vector>

#include "demcal/inverse/inversion.hpp"

namespace demcal::inverse {

struct SearchRun {
  RunResult run;                     // best sampled point and convergence record
  std::vector<Point> kept;           // points within the tolerance
  std::vector<Candidate> candidates; // cluster centres, largest cluster first
  double bandwidth = 0.0;            // in unit-box units
};

SearchRun tolerance_search(const InversionProblem& problem, const SearchSettings& settings, std::uint64_t seed,
                           const Budget& budget);

}  // namespace demcal::inverse
