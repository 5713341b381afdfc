#pragma once
// A genetic algorithm with the defaults of MATLAB's ga for a bound-constrained
// problem: population 50 (<= 5 variables) or 200, elite ceil(0.05 N),
// crossover fraction 0.8, rank fitness scaling, stochastic-uniform selection,
// scattered crossover, adaptive-feasible mutation, uniform creation inside the
// bounds, at most 100 x nvars generations, stop after 50 stall generations
// whose relative improvement is below 1e-6.
#include "demcal/inverse/optimizer.hpp"

namespace demcal::inverse {

struct GaSettings {
  int population = 0;               // 0: 50 for <= 5 variables, else 200
  double elite_fraction = 0.05;     // elite = ceil(fraction x population)
  double crossover_fraction = 0.8;
  int max_generations = 0;          // 0: 100 x nvars
  int stall_generations = 50;
  double function_tolerance = 1e-6;
};

class GeneticAlgorithm : public Optimizer {
 public:
  explicit GeneticAlgorithm(GaSettings settings) : settings_(settings) {}
  std::string name() const override { return "ga"; }
  RunResult minimize(const BatchObjective& objective, const Bounds& bounds, std::uint64_t seed,
                     const Budget& budget) const override;

 private:
  GaSettings settings_;
};

}  // namespace demcal::inverse
