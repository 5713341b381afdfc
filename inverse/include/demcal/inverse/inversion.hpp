#pragma once
// One inversion as a user asks for it: an optimiser (or the tolerance search)
// over several independent restarts, an optional local polish, and an honest
// account of the answer: the best point, the spread of each parameter over
// the restarts (or search points) that reach the targets, which parameters
// the targets do not identify, the candidate set, the range of outputs the
// domain can reach, and "unreachable" when no point meets the targets.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/inverse/optimizer.hpp"
#include "demcal/inverse/problem.hpp"

namespace demcal::inverse {

struct SearchSettings {
  int samples = 5000;      // Latin-hypercube points predicted per restart
  double tolerance = 0.05; // kept when every target is within this relative error
};

struct InversionSettings {
  std::string algorithm = "ga";  // ga, sa, sa-vfsr, wca, lhs-wca, hs or search
  Settings optimizer_settings;
  SearchSettings search;
  int restarts = 1;
  std::uint64_t seed = 1;        // restart r uses seed + r
  bool polish = false;
  Budget budget;                 // per restart
  // Reached: every target within this relative error, or the objective at or
  // below budget.target_value, or (search) every target within search.tolerance.
  double reach_tolerance = 0.01;
  int attainable_samples = 2000;  // 0: not assessed (status never "unreachable")
  double unidentified_fraction = 0.5;  // spread above this share of the range: not identified
};

struct Candidate {
  Point x;
  int size = 1;  // search points in the cluster (1 for an optimiser's restart)
  std::vector<double> predicted;
  double objective = 0.0;
  double max_relative_error = 0.0;
  bool within_tolerance = false;  // every target within the search tolerance at the centre itself
};

struct RestartRecord {
  std::uint64_t seed = 0;
  RunResult run;              // the optimiser's own result and convergence record
  Point x;                    // after the polish, when asked for
  double objective = 0.0;
  double max_relative_error = 0.0;
  bool reached = false;
  bool polished = false;
  long polish_evaluations = 0;
  std::string polish_summary;
};

struct ParameterSpread {
  std::string name;
  double low = 0.0, high = 0.0;  // bounds
  double min = 0.0, max = 0.0;   // over the points that reach the targets
  double fraction = 0.0;         // (max - min) / (high - low)
  bool identified = true;
};

struct AttainableRange {
  std::string output;
  double min = 0.0, max = 0.0;
  double target = 0.0;
  bool inside = true;
};

struct InversionResult {
  // "ok"; "unreachable" (a target outside the attainable range); "not_met"
  // (every target attainable, but the best point misses the tolerance)
  std::string status;
  Point x;
  double objective = 0.0;
  double max_relative_error = 0.0;
  std::vector<double> predicted;  // targeted outputs at x
  long evaluations = 0;
  std::vector<RestartRecord> restarts;
  std::vector<Candidate> candidates;
  std::vector<ParameterSpread> spread;
  std::string spread_basis;       // what the spread was taken over; empty when too few points
  int spread_points = 0;
  std::vector<AttainableRange> attainable;
  double wall_s = 0.0;
};

InversionResult invert(const InversionProblem& problem, const InversionSettings& settings);

// The SOLUTION.json of demcal-invert.
nlohmann::json solution_json(const InversionProblem& problem, const InversionSettings& settings,
                             const InversionResult& result);
// algorithm,restart,seed,evaluations,best_objective: one row per improvement.
std::string history_csv(const InversionSettings& settings, const InversionResult& result);

}  // namespace demcal::inverse
