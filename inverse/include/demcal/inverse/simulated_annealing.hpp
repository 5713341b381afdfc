#pragma once
// The improved simulated annealing of Wang & Cao (2017): a Cauchy
// perturbation scaled by the bound width, redrawn until the point lies
// strictly inside the bounds; Metropolis acceptance; cooling
// T_k = T0 beta^(k/N) after each Markov chain of L trials (N = number of
// variables); stop below an objective threshold or at the budget.
//
// parallel_trials = k > 1 draws k candidates per step from the same state,
// evaluates them as one batch (in parallel for a DEM-backed objective) and
// submits the best to the Metropolis test; k = 1 is the published method.
//
// The generating distribution narrows with the temperature, as in Ingber's
// fast annealing: x_new = x + (ub - lb) * s_k * C, C standard Cauchy,
// s_k = scale * T_k / T0. The VFSR variant uses Ingber's generating function
// y = sgn(u - 1/2) t [(1 + 1/t)^|2u - 1| - 1] with t = T_k / T0, x_new = x + y (ub - lb).
#include "demcal/inverse/optimizer.hpp"

namespace demcal::inverse {

struct SaSettings {
  double initial_temperature = 100.0;  // T0 (Wang & Cao)
  double cooling = 0.99;               // beta
  int markov_chain_length = 100;       // L
  double step_scale = 0.1;             // Cauchy scale at T0, as a fraction of the bound width
  bool vfsr = false;                   // Ingber's VFSR generating function
  int parallel_trials = 1;             // candidates per Markov step, best one tested (1: Wang & Cao)
};

class SimulatedAnnealing : public Optimizer {
 public:
  explicit SimulatedAnnealing(SaSettings settings) : settings_(settings) {}
  std::string name() const override { return settings_.vfsr ? "sa-vfsr" : "sa"; }
  RunResult minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                     const Budget& budget) const override;

 private:
  SaSettings settings_;
};

}  // namespace demcal::inverse
