#include "demcal/inverse/verification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <boost/math/distributions/students_t.hpp>
#include <nlohmann/json.hpp>

#include "demcal/core/number_format.hpp"

namespace demcal::inverse {

double student_t_975(int degrees_of_freedom) {
  if (degrees_of_freedom < 1) return std::numeric_limits<double>::quiet_NaN();
  return boost::math::quantile(boost::math::students_t(degrees_of_freedom), 0.975);
}

namespace {

int verdict_rank(const std::string& verdict) {
  if (verdict == kIntervalInsideBand) return 0;
  if (verdict == kMeanInsideBand) return 1;
  return 2;
}

// Where the band target -+ tolerance |target| puts the row.
std::string row_verdict(const VerificationRow& r, double tolerance) {
  if (!r.passed) return kOutside;
  const double band_low = r.target - tolerance * std::fabs(r.target), band_high = r.target + tolerance * std::fabs(r.target);
  return r.ci95_low >= band_low && r.ci95_high <= band_high ? kIntervalInsideBand : kMeanInsideBand;
}

}  // namespace

Verification verify(const std::map<std::string, double>& targets, const std::map<std::string, double>& predicted,
                     const std::vector<SeedRun>& seeds, double tolerance, const Intervals& predicted_intervals) {
  Verification v;
  v.seeds = seeds;
  v.tolerance = tolerance;
  v.passed = true;
  for (const auto& [output, target] : targets) {
    VerificationRow row;
    row.output = output;
    row.target = target;
    auto p = predicted.find(output);
    row.predicted = p == predicted.end() ? std::numeric_limits<double>::quiet_NaN() : p->second;
    auto pi = predicted_intervals.find(output);
    row.predicted_low = pi == predicted_intervals.end() ? std::numeric_limits<double>::quiet_NaN() : pi->second.first;
    row.predicted_high = pi == predicted_intervals.end() ? std::numeric_limits<double>::quiet_NaN() : pi->second.second;
    std::vector<double> values;
    for (const SeedRun& s : seeds) {
      if (!s.ok) continue;
      auto it = s.macro.find(output);
      if (it != s.macro.end() && std::isfinite(it->second)) values.push_back(it->second);
    }
    row.runs = static_cast<int>(values.size());
    double sum = 0.0;
    for (double x : values) sum += x;
    row.mean = values.empty() ? std::numeric_limits<double>::quiet_NaN() : sum / static_cast<double>(values.size());
    double ss = 0.0;
    for (double x : values) ss += (x - row.mean) * (x - row.mean);
    row.sd = values.size() > 1 ? std::sqrt(ss / static_cast<double>(values.size() - 1)) : std::numeric_limits<double>::quiet_NaN();
    row.cv_pct = 100.0 * row.sd / std::fabs(row.mean);
    row.relative_error_pct = 100.0 * (row.mean - target) / std::fabs(target);
    row.passed = row.runs >= 2 && std::fabs(row.relative_error_pct) <= 100.0 * tolerance;
    const double half_width = row.runs >= 2 ? student_t_975(row.runs - 1) * row.sd / std::sqrt(double(row.runs))
                                            : std::numeric_limits<double>::quiet_NaN();
    row.ci95_low = row.mean - half_width;
    row.ci95_high = row.mean + half_width;
    row.half_width_pct = 100.0 * half_width / std::fabs(target);
    row.verdict = row_verdict(row, tolerance);
    v.passed = v.passed && row.passed;
    v.rows.push_back(row);
  }
  v.verdict = kIntervalInsideBand;
  for (const VerificationRow& r : v.rows)
    if (verdict_rank(r.verdict) > verdict_rank(v.verdict)) v.verdict = r.verdict;
  if (v.rows.empty()) v.verdict = kOutside;
  return v;
}

bool interval_outside_band(const Verification& v) {
  for (const VerificationRow& r : v.rows) {
    if (r.runs < 2 || !std::isfinite(r.ci95_low)) continue;
    const double band_low = r.target - v.tolerance * std::fabs(r.target);
    const double band_high = r.target + v.tolerance * std::fabs(r.target);
    if (r.ci95_low > band_high || r.ci95_high < band_low) return true;
  }
  return false;
}

int seeds_wanted(const Verification& v, int max_seeds) {
  const int have = static_cast<int>(v.seeds.size());
  if (have >= max_seeds || interval_outside_band(v)) return have;
  int want = have;
  for (const VerificationRow& r : v.rows) {
    if (r.runs >= 2 && r.half_width_pct <= 100.0 * v.tolerance) continue;
    if (r.runs < 2 || !std::isfinite(r.sd)) {  // no spread yet: two more runs measure one
      want = std::max(want, have + 2);
      continue;
    }
    // Smallest n with t(n-1) sd / sqrt(n) <= tolerance |target|, the seeds that
    // failed so far counted as lost at the same rate.
    const double allowed = v.tolerance * std::fabs(r.target);
    int n = r.runs + 1;
    while (n < max_seeds && student_t_975(n - 1) * r.sd / std::sqrt(double(n)) > allowed) ++n;
    const double lost_rate = 1.0 - double(r.runs) / double(std::max(have, 1));
    want = std::max(want, static_cast<int>(std::ceil(double(n) / std::max(1.0 - lost_rate, 0.5))));
  }
  return std::min(want, max_seeds);
}

namespace {

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::string significant(double value) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

}  // namespace

std::string verification_markdown(const Verification& v) {
  std::ostringstream md;
  int ok = 0;
  for (const SeedRun& s : v.seeds) ok += s.ok;
  bool any_interval = false;
  for (const VerificationRow& r : v.rows) any_interval = any_interval || std::isfinite(r.predicted_low);
  md << "| output | target | predicted |" << (any_interval ? " its 95 % prediction interval |" : "")
     << " DEM mean | SD | CV % | 95 % interval of the mean | half-width % | relative error % | within "
     << fixed(100 * v.tolerance, 1) << " % | verdict |\n|---|---|---|" << (any_interval ? "---|" : "")
     << "---|---|---|---|---|---|---|---|\n";
  for (const VerificationRow& r : v.rows)
    md << "| " << r.output << " | " << significant(r.target) << " | " << significant(r.predicted) << " | "
       << (any_interval ? (std::isfinite(r.predicted_low)
                               ? significant(r.predicted_low) + " to " + significant(r.predicted_high) + " | "
                               : std::string("- | "))
                        : std::string())
       << significant(r.mean) << " | " << significant(r.sd) << " | " << fixed(r.cv_pct, 2) << " | "
       << (std::isfinite(r.ci95_low) ? significant(r.ci95_low) + " to " + significant(r.ci95_high) : std::string("-"))
       << " | " << fixed(r.half_width_pct, 2) << " | " << fixed(r.relative_error_pct, 2) << " | "
       << (r.passed ? "yes" : "no") << " | " << r.verdict << " |\n";
  md << "\n" << ok << " of " << v.seeds.size() << " DEM seeds ran";
  for (const SeedRun& s : v.seeds)
    if (!s.ok) md << "; seed " << s.seed << " failed: " << s.reason;
  md << ". Verification " << (v.passed ? "passed" : "failed") << " (" << v.verdict << ")";
  if (!v.seeds_stop_reason.empty()) md << "; seeds stopped: " << v.seeds_stop_reason;
  md << ".\n";
  return md.str();
}

std::string verification_csv(const Verification& v) {
  std::ostringstream csv;
  csv << "output,target,predicted,mean,sd,cv_pct,ci95_low,ci95_high,half_width_pct,relative_error_pct,runs,passed,"
         "verdict\n";
  auto num = [](double x) { return std::isfinite(x) ? format_double(x) : std::string("nan"); };
  for (const VerificationRow& r : v.rows)
    csv << r.output << ',' << num(r.target) << ',' << num(r.predicted) << ',' << num(r.mean) << ',' << num(r.sd) << ','
        << num(r.cv_pct) << ',' << num(r.ci95_low) << ',' << num(r.ci95_high) << ',' << num(r.half_width_pct) << ','
        << num(r.relative_error_pct) << ',' << r.runs << ',' << (r.passed ? 1 : 0) << ',' << r.verdict << '\n';
  return csv.str();
}

nlohmann::json verification_json(const Verification& v) {
  using nlohmann::json;
  auto num = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  json rows = json::object();
  for (const VerificationRow& r : v.rows)
    rows[r.output] = {{"target", num(r.target)}, {"predicted", num(r.predicted)},
                      {"predicted_interval_95", std::isfinite(r.predicted_low)
                                                    ? json::array({r.predicted_low, r.predicted_high}) : json(nullptr)},
                      {"mean", num(r.mean)}, {"sd", num(r.sd)},
                      {"cv_pct", num(r.cv_pct)}, {"ci95_low", num(r.ci95_low)}, {"ci95_high", num(r.ci95_high)},
                      {"half_width_pct", num(r.half_width_pct)}, {"relative_error_pct", num(r.relative_error_pct)},
                      {"runs", r.runs}, {"passed", r.passed}, {"verdict", r.verdict}};
  json seeds = json::array();
  for (const SeedRun& s : v.seeds) {
    json m = json::object();
    for (const auto& [k, x] : s.macro) m[k] = num(x);
    seeds.push_back({{"seed", s.seed}, {"status", s.ok ? "ok" : "failed"}, {"reason", s.reason}, {"macro", m}});
  }
  json out = {{"passed", v.passed}, {"verdict", v.verdict}, {"tolerance", v.tolerance}, {"outputs", rows}, {"seeds", seeds}};
  if (!v.seeds_stop_reason.empty()) out["seeds_stop_reason"] = v.seeds_stop_reason;
  return out;
}

}  // namespace demcal::inverse
