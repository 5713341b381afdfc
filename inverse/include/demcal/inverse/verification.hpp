#pragma once
// The verification table of a calibration, as the literature prints it: per
// output the target, the mean over the DEM seeds, standard deviation,
// coefficient of variation and relative error, and whether the error is
// within the tolerance. Knows nothing of how the runs were made.
#include <cstdint>
#include <map>
#include <string>
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
  double mean = 0.0, sd = 0.0, cv_pct = 0.0, relative_error_pct = 0.0;
  int runs = 0;            // seeds that ran and gave this output
  bool passed = false;     // |relative error| <= tolerance
};

struct Verification {
  std::vector<VerificationRow> rows;
  std::vector<SeedRun> seeds;
  double tolerance = 0.05;
  bool passed = false;  // every row passed and at least two seeds ran
};

Verification verify(const std::map<std::string, double>& targets, const std::map<std::string, double>& predicted,
                     const std::vector<SeedRun>& seeds, double tolerance);

std::string verification_markdown(const Verification& v);
std::string verification_csv(const Verification& v);
nlohmann::json verification_json(const Verification& v);

}  // namespace demcal::inverse
