#pragma once
// The water cycle algorithm (Eskandar, Sadollah, Bahreininejad & Hamdi 2012)
// with the authors' defaults: population 50, Nsr = 4 (the sea and three
// rivers), C = 2, evaporation distance dmax = 1e-16 decreasing by
// dmax / max_iterations, raining of new streams at random positions (near the
// sea for the sea's own streams). The LHS-WCA of Ma et al. (2022) starts from
// a Latin hypercube instead of uniform random points.
#include "demcal/inverse/optimizer.hpp"

namespace demcal::inverse {

struct WcaSettings {
  int population = 50;
  int rivers_and_sea = 4;     // Nsr
  double c = 2.0;             // C
  double dmax = 1e-16;
  int max_iterations = 0;     // 0: from the budget
  bool latin_hypercube_start = false;
};

class WaterCycle : public Optimizer {
 public:
  explicit WaterCycle(WcaSettings settings) : settings_(settings) {}
  std::string name() const override { return settings_.latin_hypercube_start ? "lhs-wca" : "wca"; }
  RunResult minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                     const Budget& budget) const override;

 private:
  WcaSettings settings_;
};

}  // namespace demcal::inverse
