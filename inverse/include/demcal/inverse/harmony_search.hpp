#pragma once
// Harmony search (Geem, Kim & Loganathan 2001) in its improved form for
// continuous variables (Mahdavi, Fesanghary & Damangir 2007): a memory of
// the best HMS points; each new point takes every variable from a remembered
// point with probability HMCR (then shifts it by up to the bandwidth with the
// pitch-adjusting rate PAR) or draws it anew within the bounds, and replaces
// the worst remembered point when it is better. PAR rises linearly and the
// bandwidth falls exponentially over the run, from exploring to refining.
// Ma et al. (2022) compared it with the water cycle on their slope. Several
// new points per iteration (`improvisations`) let a DEM-backed objective run
// them side by side.
#include "demcal/inverse/optimizer.hpp"

namespace demcal::inverse {

struct HsSettings {
  int memory_size = 10;           // HMS
  double hmcr = 0.95;             // harmony memory considering rate
  double par_min = 0.35, par_max = 0.99;
  double bandwidth_max = 0.05;    // as a fraction of each variable's range
  double bandwidth_min = 1e-4;
  int improvisations = 1;         // new points per iteration
};

class HarmonySearch : public Optimizer {
 public:
  explicit HarmonySearch(HsSettings settings) : settings_(settings) {}
  std::string name() const override { return "hs"; }
  RunResult minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                     const Budget& budget) const override;

 private:
  HsSettings settings_;
};

}  // namespace demcal::inverse
