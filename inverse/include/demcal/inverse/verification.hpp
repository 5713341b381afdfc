#pragma once
// The verification table of a calibration, as the literature prints it: per
// output the target, the mean over the DEM seeds, standard deviation,
// coefficient of variation and relative error, and whether the error is
// within the tolerance; beside it the 95 % confidence interval of the mean
// (Student t), so a reader sees whether the seeds can tell a pass from noise.
// Knows nothing of how the runs were made.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace demcal::inverse {

struct SeedRun {
  std::uint64_t seed = 0;
  bool ok = false;
  std::string reason;                   // why it failed
  std::map<std::string, double> macro;  // DEM outputs
};

struct VerificationRow {
  std::string output;
  double target = 0.0;
  double predicted = 0.0;  // by the surrogate at the solution (NaN when unknown)
  // The surrogate's 95 % prediction interval of one run there (NaN when it gives none).
  double predicted_low = 0.0, predicted_high = 0.0;
  double mean = 0.0, sd = 0.0, cv_pct = 0.0, relative_error_pct = 0.0;
  int runs = 0;            // seeds that ran and gave this output
  bool passed = false;     // |relative error| <= tolerance
  // 95 % confidence interval of the mean: mean -+ t(0.975, runs-1) sd / sqrt(runs) (NaN below 2 runs).
  double ci95_low = 0.0, ci95_high = 0.0;
  double half_width_pct = 0.0;  // the interval's half-width in % of |target|
  std::string verdict;          // kInsideBand, kMeanInsideBand or kOutside
};

// The verdicts, best first: the whole interval lies within target -+ tolerance;
// only the mean does; the mean does not (or fewer than two seeds ran).
inline constexpr const char* kIntervalInsideBand = "interval_inside_band";
inline constexpr const char* kMeanInsideBand = "mean_inside_band";
inline constexpr const char* kOutside = "outside";

struct Verification {
  std::vector<VerificationRow> rows;
  std::vector<SeedRun> seeds;
  double tolerance = 0.05;
  bool passed = false;  // every row passed and at least two seeds ran
  std::string verdict;  // the worst of the rows' verdicts
  std::string seeds_stop_reason;  // why no more seeds were added (set by the caller that adds them)
};

using Intervals = std::map<std::string, std::pair<double, double>>;
Verification verify(const std::map<std::string, double>& targets, const std::map<std::string, double>& predicted,
                     const std::vector<SeedRun>& seeds, double tolerance, const Intervals& predicted_intervals = {});

// How many seeds in all the verification wants: the smallest n at which every
// output's half-width t(0.975, n-1) sd / sqrt(n) would be at most the tolerance
// with the spread measured so far, capped at max_seeds. Returns the seeds it has
// when every half-width is already small enough, or when some output's whole
// interval lies outside the band (more seeds would narrow it, not move it in).
int seeds_wanted(const Verification& v, int max_seeds);
// Whether some output's interval lies entirely outside target -+ tolerance.
bool interval_outside_band(const Verification& v);
// Student t quantile t(0.975, dof): the 95 % two-sided factor.
double student_t_975(int degrees_of_freedom);

std::string verification_markdown(const Verification& v);
std::string verification_csv(const Verification& v);
nlohmann::json verification_json(const Verification& v);

}  // namespace demcal::inverse
