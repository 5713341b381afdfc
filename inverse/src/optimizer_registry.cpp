#include <set>

#include "demcal/core/error.hpp"
#include "demcal/inverse/genetic_algorithm.hpp"
#include "demcal/inverse/harmony_search.hpp"
#include "demcal/inverse/optimizer.hpp"
#include "demcal/inverse/simulated_annealing.hpp"
#include "demcal/inverse/water_cycle.hpp"

namespace demcal::inverse {

namespace {

// Reads the settings an optimiser knows; any other name is an error.
class SettingsReader {
 public:
  SettingsReader(const Settings& settings, std::string algorithm) : settings_(settings), algorithm_(std::move(algorithm)) {}
  double get(const std::string& key, double fallback) {
    known_.insert(key);
    auto it = settings_.find(key);
    return it == settings_.end() ? fallback : it->second;
  }
  int get_int(const std::string& key, int fallback) { return static_cast<int>(get(key, fallback)); }
  void check() const {
    for (const auto& entry : settings_)
      if (!known_.count(entry.first)) {
        std::string list;
        for (const std::string& k : known_) list += (list.empty() ? "" : ", ") + k;
        throw Error("setting \"" + entry.first + "\" does not apply to " + algorithm_ + " (its settings: " + list + ")");
      }
  }

 private:
  const Settings& settings_;
  std::string algorithm_;
  std::set<std::string> known_;
};

}  // namespace

std::vector<std::string> optimizer_names() { return {"ga", "sa", "sa-vfsr", "wca", "lhs-wca", "hs"}; }

std::unique_ptr<Optimizer> make_optimizer(const std::string& name, const Settings& settings) {
  SettingsReader r(settings, name);
  std::unique_ptr<Optimizer> optimizer;
  if (name == "ga") {
    GaSettings s;
    s.population = r.get_int("population", s.population);
    s.elite_fraction = r.get("elite_fraction", s.elite_fraction);
    s.crossover_fraction = r.get("crossover_fraction", s.crossover_fraction);
    s.max_generations = r.get_int("generations", s.max_generations);
    s.stall_generations = r.get_int("stall_generations", s.stall_generations);
    s.function_tolerance = r.get("function_tolerance", s.function_tolerance);
    if (s.population < 0 || s.population == 1 || !(s.crossover_fraction >= 0 && s.crossover_fraction <= 1) ||
        !(s.elite_fraction >= 0 && s.elite_fraction < 1) || s.stall_generations < 1)
      throw Error("ga: population >= 2, 0 <= crossover_fraction <= 1, 0 <= elite_fraction < 1, stall_generations >= 1");
    optimizer = std::make_unique<GeneticAlgorithm>(s);
  } else if (name == "sa" || name == "sa-vfsr") {
    SaSettings s;
    s.vfsr = name == "sa-vfsr";
    s.initial_temperature = r.get("T0", s.initial_temperature);
    s.cooling = r.get("beta", s.cooling);
    s.markov_chain_length = r.get_int("markov_chain_length", s.markov_chain_length);
    s.step_scale = r.get("step_scale", s.step_scale);
    s.parallel_trials = r.get_int("parallel_trials", s.parallel_trials);
    if (!(s.initial_temperature > 0) || !(s.cooling > 0 && s.cooling < 1) || s.markov_chain_length < 1 ||
        !(s.step_scale > 0) || s.parallel_trials < 1)
      throw Error(name + ": T0 > 0, 0 < beta < 1, markov_chain_length >= 1, step_scale > 0, parallel_trials >= 1");
    optimizer = std::make_unique<SimulatedAnnealing>(s);
  } else if (name == "wca" || name == "lhs-wca") {
    WcaSettings s;
    s.latin_hypercube_start = name == "lhs-wca";
    s.population = r.get_int("population", s.population);
    s.rivers_and_sea = r.get_int("nsr", s.rivers_and_sea);
    s.c = r.get("C", s.c);
    s.dmax = r.get("dmax", s.dmax);
    s.max_iterations = r.get_int("iterations", s.max_iterations);
    optimizer = std::make_unique<WaterCycle>(s);
  } else if (name == "hs") {
    HsSettings s;
    s.memory_size = r.get_int("hms", s.memory_size);
    s.hmcr = r.get("hmcr", s.hmcr);
    s.par_min = r.get("par_min", s.par_min);
    s.par_max = r.get("par_max", s.par_max);
    s.bandwidth_max = r.get("bw_max", s.bandwidth_max);
    s.bandwidth_min = r.get("bw_min", s.bandwidth_min);
    s.improvisations = r.get_int("improvisations", s.improvisations);
    if (s.memory_size < 2 || !(s.hmcr >= 0 && s.hmcr <= 1) || !(s.par_min >= 0 && s.par_min <= s.par_max && s.par_max <= 1) ||
        !(s.bandwidth_min > 0 && s.bandwidth_min <= s.bandwidth_max && s.bandwidth_max <= 1) || s.improvisations < 1)
      throw Error("hs: hms >= 2, 0 <= hmcr <= 1, 0 <= par_min <= par_max <= 1, 0 < bw_min <= bw_max <= 1, improvisations >= 1");
    optimizer = std::make_unique<HarmonySearch>(s);
  } else {
    std::string list;
    for (const std::string& n : optimizer_names()) list += (list.empty() ? "" : ", ") + n;
    throw Error("unknown algorithm \"" + name + "\" (expected " + list + " or search)");
  }
  r.check();
  return optimizer;
}

}  // namespace demcal::inverse
