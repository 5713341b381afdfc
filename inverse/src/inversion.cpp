#include "demcal/inverse/inversion.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/doe/space_filling.hpp"
#include "demcal/inverse/polish.hpp"
#include "demcal/inverse/tolerance_search.hpp"

namespace demcal::inverse {

namespace {

double normalised_distance(const Point& a, const Point& b, const Bounds& bounds) {
  double d = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    double e = (a[j] - b[j]) / (bounds.high[j] - bounds.low[j]);
    d += e * e;
  }
  return std::sqrt(d);
}

std::vector<AttainableRange> attainable_ranges(const InversionProblem& problem, int samples, std::uint64_t seed,
                                               const std::vector<double>& best_predicted) {
  const Bounds& b = problem.bounds();
  std::vector<AttainableRange> ranges;
  for (const Target& t : problem.targets()) ranges.push_back({t.output, INFINITY, -INFINITY, t.value, false});
  auto extend = [&](const std::vector<double>& y) {
    for (std::size_t i = 0; i < y.size(); ++i) {
      if (!std::isfinite(y[i])) continue;
      ranges[i].min = std::min(ranges[i].min, y[i]);
      ranges[i].max = std::max(ranges[i].max, y[i]);
    }
  };
  if (samples > 1) {
    doe::LhsOptions lhs;
    lhs.runs = samples;
    lhs.factors = static_cast<int>(b.size());
    lhs.seed = seed ^ 0xa77a;
    Eigen::MatrixXd unit = doe::latin_hypercube(lhs).coded;
    Point x(b.size());
    for (Eigen::Index i = 0; i < unit.rows(); ++i) {
      for (std::size_t j = 0; j < x.size(); ++j) x[j] = b.low[j] + unit(i, static_cast<Eigen::Index>(j)) * (b.high[j] - b.low[j]);
      extend(problem.predict_targets(x));
    }
  }
  extend(best_predicted);
  for (AttainableRange& r : ranges) r.inside = r.target >= r.min && r.target <= r.max;
  return ranges;
}

void record_spread(InversionResult& result, const InversionProblem& problem, const std::vector<Point>& points,
                   const std::string& basis, double unidentified_fraction) {
  if (points.size() < 2) return;
  result.spread_basis = basis;
  result.spread_points = static_cast<int>(points.size());
  const Bounds& b = problem.bounds();
  for (std::size_t j = 0; j < b.size(); ++j) {
    ParameterSpread s;
    s.name = problem.parameter_names()[j];
    s.low = b.low[j];
    s.high = b.high[j];
    s.min = INFINITY;
    s.max = -INFINITY;
    for (const Point& p : points) {
      s.min = std::min(s.min, p[j]);
      s.max = std::max(s.max, p[j]);
    }
    s.fraction = (s.max - s.min) / (s.high - s.low);
    s.identified = s.fraction <= unidentified_fraction;
    result.spread.push_back(s);
  }
}

}  // namespace

InversionResult invert(const InversionProblem& problem, const InversionSettings& settings) {
  if (settings.restarts < 1) throw Error("--restarts must be at least 1");
  if (!(settings.reach_tolerance > 0)) throw Error("--reach-tolerance must be positive");
  const bool search = settings.algorithm == "search";
  if (search && settings.search.samples < 2) throw Error("search: --samples must be at least 2");
  std::unique_ptr<Optimizer> optimizer;
  if (!search) optimizer = make_optimizer(settings.algorithm, settings.optimizer_settings);
  else if (!settings.optimizer_settings.empty())
    throw Error("setting \"" + settings.optimizer_settings.begin()->first + "\" does not apply to search");

  // A run meets the targets when every relative error is within the reach
  // tolerance, or when it stopped at the objective threshold the user set (the
  // annealing's 10 %), or (search) when it lies within the search tolerance.
  // A minimisation has no target to miss: its best point is its answer.
  const bool minimise = problem.objective_kind() == ObjectiveKind::Minimise;
  if (minimise && search)
    throw Error("--objective minimise has no targets to search within a tolerance of; use an optimiser");
  if (minimise && settings.polish)
    throw Error("--polish fits the outputs to their targets by least squares; --objective minimise has none to fit");
  auto meets = [&](double objective, double max_error) {
    return minimise || max_error <= settings.reach_tolerance || objective <= settings.budget.target_value ||
           (search && max_error <= settings.search.tolerance);
  };
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> targets = problem.target_values();
  InversionResult result;
  std::vector<Point> search_kept;
  std::vector<Candidate> search_candidates;
  for (int r = 0; r < settings.restarts; ++r) {
    RestartRecord record;
    record.seed = settings.seed + static_cast<std::uint64_t>(r);
    if (search) {
      SearchRun s = tolerance_search(problem, settings.search, record.seed, settings.budget);
      record.run = s.run;
      search_kept.insert(search_kept.end(), s.kept.begin(), s.kept.end());
      search_candidates.insert(search_candidates.end(), s.candidates.begin(), s.candidates.end());
      // The best of the run or of its cluster centres.
      record.x = s.run.x;
      for (const Candidate& c : s.candidates)
        if (c.objective < problem.objective(record.x)) record.x = c.x;
    } else {
      record.run = optimizer->minimize(problem.batch_objective(), problem.bounds(), record.seed, settings.budget);
      record.x = record.run.x;
    }
    if (record.x.empty()) throw Error("invert: the optimiser evaluated no point (budget 0?)");
    record.objective = problem.objective(record.x);
    if (settings.polish) {
      PolishResult p = polish(problem, record.x);
      record.polished = true;
      record.polish_evaluations = p.evaluations;
      record.polish_summary = p.summary;
      double polished = problem.objective(p.x);
      if (polished < record.objective) {
        record.x = p.x;
        record.objective = polished;
      }
    }
    record.max_relative_error = max_relative_error(problem.predict_targets(record.x), targets);
    record.reached = meets(record.objective, record.max_relative_error);
    result.evaluations += record.run.evaluations + record.polish_evaluations;
    result.restarts.push_back(record);
  }

  const RestartRecord& best = *std::min_element(result.restarts.begin(), result.restarts.end(),
                                                [](const RestartRecord& a, const RestartRecord& b) { return a.objective < b.objective; });
  result.x = best.x;
  result.objective = best.objective;
  result.predicted = problem.predict_targets(best.x);
  result.max_relative_error = best.max_relative_error;
  result.status = best.reached ? "ok" : "not_met";

  if (search) {
    result.candidates = search_candidates;
    std::stable_sort(result.candidates.begin(), result.candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.size > b.size; });
    record_spread(result, problem, search_kept, "search points within the tolerance", settings.unidentified_fraction);
  } else {
    std::vector<Point> reached;
    for (const RestartRecord& r : result.restarts) {
      if (!r.reached) continue;
      reached.push_back(r.x);
      bool duplicate = false;
      for (const Candidate& c : result.candidates) duplicate = duplicate || normalised_distance(c.x, r.x, problem.bounds()) < 1e-3;
      if (duplicate) continue;
      Candidate c;
      c.x = r.x;
      c.predicted = problem.predict_targets(r.x);
      c.objective = r.objective;
      c.max_relative_error = r.max_relative_error;
      c.within_tolerance = true;
      result.candidates.push_back(c);
    }
    record_spread(result, problem, reached, "restarts that reached the targets", settings.unidentified_fraction);
  }
  // Zero samples: not assessed (each sample would be a DEM run in the loop).
  if (settings.attainable_samples > 0)
    result.attainable = attainable_ranges(problem, settings.attainable_samples, settings.seed, result.predicted);
  // Unreachable only when a target lies outside what the domain can give;
  // otherwise a miss is the optimiser's and is said so (status not_met).
  if (result.status == "not_met")
    for (const AttainableRange& a : result.attainable)
      if (!a.inside) result.status = "unreachable";
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

namespace {

using nlohmann::json;

json named(const std::vector<std::string>& names, const Point& x) {
  json out = json::object();
  for (std::size_t j = 0; j < names.size() && j < x.size(); ++j) out[names[j]] = x[j];
  return out;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

json solution_json(const InversionProblem& problem, const InversionSettings& settings, const InversionResult& result) {
  const std::vector<std::string>& names = problem.parameter_names();
  json predicted = json::object();
  for (const auto& [name, value] : problem.predict_all(result.x)) predicted[name] = value;
  json intervals = json::object();
  for (const auto& [name, range] : problem.prediction_intervals_95(result.x))
    intervals[name] = {finite_or_null(range.first), finite_or_null(range.second)};
  json targets = json::object(), errors = json::object();
  for (std::size_t i = 0; i < problem.targets().size(); ++i) {
    targets[problem.targets()[i].output] = problem.targets()[i].value;
    errors[problem.targets()[i].output] = (result.predicted[i] - problem.targets()[i].value) / std::fabs(problem.targets()[i].value);
  }
  json restarts = json::array();
  for (const RestartRecord& r : result.restarts) {
    json entry = {{"seed", r.seed}, {"x", named(names, r.x)}, {"objective", finite_or_null(r.objective)},
                  {"max_relative_error", finite_or_null(r.max_relative_error)}, {"evaluations", r.run.evaluations},
                  {"stop_reason", r.run.stop_reason}, {"reached", r.reached}};
    if (r.polished) entry["polish"] = {{"evaluations", r.polish_evaluations}, {"summary", r.polish_summary}};
    restarts.push_back(entry);
  }
  json candidates = json::array();
  for (const Candidate& c : result.candidates) {
    json p = json::object();
    for (std::size_t i = 0; i < problem.targets().size(); ++i) p[problem.targets()[i].output] = c.predicted[i];
    candidates.push_back({{"x", named(names, c.x)}, {"size", c.size}, {"predicted", p},
                          {"objective", finite_or_null(c.objective)}, {"max_relative_error", finite_or_null(c.max_relative_error)},
                          {"within_tolerance", c.within_tolerance}});
  }
  json spread = json::object(), unidentified = json::array();
  for (const ParameterSpread& s : result.spread) {
    spread[s.name] = {{"min", s.min}, {"max", s.max}, {"low", s.low}, {"high", s.high}, {"fraction_of_range", s.fraction},
                      {"identified", s.identified}};
    if (!s.identified) unidentified.push_back(s.name);
  }
  json free = json::object();
  for (const InputRange& f : problem.free_parameters()) {
    free[f.name] = {{"low", f.low}, {"high", f.high}, {"note", "no model uses it: not identified by these targets"}};
    unidentified.push_back(f.name);
  }
  json attainable = json::object();
  for (const AttainableRange& a : result.attainable)
    attainable[a.output] = {{"min", a.min}, {"max", a.max}, {"target", a.target}, {"inside", a.inside}};
  json out = {{"status", result.status},
              {"x", named(names, result.x)},
              {"predicted", predicted},
              {"prediction_interval_95", intervals},
              {"objective", finite_or_null(result.objective)},
              {"objective_kind", to_string(problem.objective_kind())},
              {"targets", targets},
              {"relative_errors", errors},
              {"max_relative_error", finite_or_null(result.max_relative_error)},
              {"reach_tolerance", settings.reach_tolerance},
              {"evaluations", result.evaluations},
              {"algorithm", settings.algorithm},
              {"seed", settings.seed},
              {"polish", settings.polish},
              {"restarts", restarts},
              {"candidates", candidates},
              {"spread", spread},
              {"spread_basis", result.spread_basis},
              {"spread_points", result.spread_points},
              {"unidentified", unidentified},
              {"free_parameters", free},
              {"attainable", attainable},
              {"warnings", problem.warnings()},
              {"wall_s", result.wall_s}};
  if (result.status == "unreachable") {
    std::string why;
    for (const AttainableRange& a : result.attainable)
      if (!a.inside)
        why += (why.empty() ? "" : "; ") + a.output + " = " + format_double(a.target) + " lies outside the attainable [" +
               format_double(a.min) + ", " + format_double(a.max) + "]";
    out["reason"] = why;
    out["nearest_attainable"] = predicted;
  } else if (result.status == "not_met") {
    out["reason"] = std::string(result.attainable.empty() ? "the attainable ranges were not assessed; "
                                                          : "every target lies inside its attainable range, but ") +
                    "the best point found misses them by " +
                    format_double(result.max_relative_error) +
                    " (max relative error): more budget, restarts, --polish or another algorithm may meet them, or "
                    "they may not be attainable together";
    out["nearest_attainable"] = predicted;
  }
  if (result.spread_basis.empty())
    out["spread_note"] = "fewer than two runs met the targets: run --restarts R (R >= 2) to see which parameters they identify";
  return out;
}

std::string history_csv(const InversionSettings& settings, const InversionResult& result) {
  std::ostringstream csv;
  csv << "algorithm,restart,seed,evaluations,best_objective\n";
  for (std::size_t r = 0; r < result.restarts.size(); ++r)
    for (const HistoryPoint& h : result.restarts[r].run.history)
      csv << settings.algorithm << ',' << r << ',' << result.restarts[r].seed << ',' << h.evaluations << ','
          << format_double(h.best) << '\n';
  return csv.str();
}

}  // namespace demcal::inverse
