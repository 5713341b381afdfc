#include "demcal/inverse/verification.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/number_format.hpp"

namespace demcal::inverse {

Verification verify(const std::map<std::string, double>& targets, const std::map<std::string, double>& predicted,
                     const std::vector<SeedRun>& seeds, double tolerance) {
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
    v.passed = v.passed && row.passed;
    v.rows.push_back(row);
  }
  return v;
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
  md << "| output | target | predicted | DEM mean | SD | CV % | relative error % | within " << fixed(100 * v.tolerance, 1)
     << " % |\n|---|---|---|---|---|---|---|---|\n";
  for (const VerificationRow& r : v.rows)
    md << "| " << r.output << " | " << significant(r.target) << " | " << significant(r.predicted) << " | "
       << significant(r.mean) << " | " << significant(r.sd) << " | " << fixed(r.cv_pct, 2) << " | "
       << fixed(r.relative_error_pct, 2) << " | " << (r.passed ? "yes" : "no") << " |\n";
  md << "\n" << ok << " of " << v.seeds.size() << " DEM seeds ran";
  for (const SeedRun& s : v.seeds)
    if (!s.ok) md << "; seed " << s.seed << " failed: " << s.reason;
  md << ". Verification " << (v.passed ? "passed" : "failed") << ".\n";
  return md.str();
}

std::string verification_csv(const Verification& v) {
  std::ostringstream csv;
  csv << "output,target,predicted,mean,sd,cv_pct,relative_error_pct,runs,passed\n";
  auto num = [](double x) { return std::isfinite(x) ? format_double(x) : std::string("nan"); };
  for (const VerificationRow& r : v.rows)
    csv << r.output << ',' << num(r.target) << ',' << num(r.predicted) << ',' << num(r.mean) << ',' << num(r.sd) << ','
        << num(r.cv_pct) << ',' << num(r.relative_error_pct) << ',' << r.runs << ',' << (r.passed ? 1 : 0) << '\n';
  return csv.str();
}

nlohmann::json verification_json(const Verification& v) {
  using nlohmann::json;
  auto num = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  json rows = json::object();
  for (const VerificationRow& r : v.rows)
    rows[r.output] = {{"target", num(r.target)}, {"predicted", num(r.predicted)}, {"mean", num(r.mean)}, {"sd", num(r.sd)},
                      {"cv_pct", num(r.cv_pct)}, {"relative_error_pct", num(r.relative_error_pct)}, {"runs", r.runs},
                      {"passed", r.passed}};
  json seeds = json::array();
  for (const SeedRun& s : v.seeds) {
    json m = json::object();
    for (const auto& [k, x] : s.macro) m[k] = num(x);
    seeds.push_back({{"seed", s.seed}, {"status", s.ok ? "ok" : "failed"}, {"reason", s.reason}, {"macro", m}});
  }
  return {{"passed", v.passed}, {"tolerance", v.tolerance}, {"outputs", rows}, {"seeds", seeds}};
}

}  // namespace demcal::inverse
