#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/number_format.hpp"
#include "demcal/surrogate/f_test.hpp"
#include "demcal/surrogate/json_numbers.hpp"
#include "demcal/surrogate/reports.hpp"

namespace demcal::surrogate {

using nlohmann::json;

std::string format_number(double value, int significant) {
  if (std::isnan(value)) return "";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant, value);
  return buffer;
}

std::string format_p(double p) {
  if (std::isnan(p)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", p);
  return buffer;
}

namespace {

std::string joined(const std::vector<std::string>& parts, const char* separator = " / ") {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

}  // namespace

std::string range_markdown(const std::vector<RangeAnalysis>& analyses) {
  std::ostringstream md;
  for (const RangeAnalysis& a : analyses) {
    md << "### Range analysis of " << a.response << " (" << a.runs << " runs, mean " << format_number(a.grand_mean)
       << ")\n\n| Factor | Levels | n_i | K_i (sum) | k_i (mean) | R | Rank |\n|---|---|---|---|---|---|---|\n";
    for (const FactorRange& f : a.factors) {
      std::vector<std::string> levels, counts, sums, means;
      for (const LevelSummary& l : f.levels) {
        levels.push_back(format_number(l.level));
        counts.push_back(std::to_string(l.count));
        sums.push_back(format_number(l.sum));
        means.push_back(format_number(l.mean));
      }
      md << "| " << f.factor << " | " << joined(levels) << " | " << joined(counts) << " | " << joined(sums) << " | "
         << joined(means) << " | " << format_number(f.range) << " | " << f.rank << " |\n";
    }
    std::vector<std::pair<int, std::string>> order;
    for (const FactorRange& f : a.factors) order.push_back({f.rank, f.factor});
    std::sort(order.begin(), order.end());
    std::vector<std::string> names;
    for (const auto& entry : order) names.push_back(entry.second);
    md << "\nFactors by range (largest effect first): " << joined(names, " > ") << "\n\n";
  }
  return md.str();
}

json range_json(const std::vector<RangeAnalysis>& analyses) {
  json out = json::object();
  for (const RangeAnalysis& a : analyses) {
    json factors = json::object(), order = json::array();
    for (const FactorRange& f : a.factors) {
      order.push_back(f.factor);
      json levels = json::array(), counts = json::array(), sums = json::array(), means = json::array();
      for (const LevelSummary& l : f.levels) {
        levels.push_back(l.level);
        counts.push_back(l.count);
        sums.push_back(l.sum);
        means.push_back(l.mean);
      }
      factors[f.factor] = {{"levels", levels}, {"count", counts}, {"K", sums}, {"k", means},
                           {"R", f.range}, {"rank", f.rank}, {"best_level", f.best_level}};
    }
    out[a.response] = {{"grand_mean", a.grand_mean}, {"runs", a.runs}, {"factor_order", order}, {"factors", factors}};
  }
  return out;
}

std::string range_csv(const std::vector<RangeAnalysis>& analyses) {
  std::ostringstream csv;
  csv << "response,factor,level,count,K,k,R,rank\n";
  for (const RangeAnalysis& a : analyses)
    for (const FactorRange& f : a.factors)
      for (const LevelSummary& l : f.levels)
        csv << a.response << ',' << f.factor << ',' << format_double(l.level) << ',' << l.count << ','
            << format_double(l.sum) << ',' << format_double(l.mean) << ',' << format_double(f.range) << ',' << f.rank
            << '\n';
  return csv.str();
}

namespace {

std::string significance_word(double p) {
  std::string mark = significance_mark(p);
  if (mark == "**") return "** highly significant";
  if (mark == "*") return "* significant";
  return "";
}

}  // namespace

std::string anova_markdown(const std::vector<DesignAnova>& tables) {
  std::ostringstream md;
  for (const DesignAnova& t : tables) {
    md << "### Analysis of variance of " << t.response << " (adjusted SS; error: " << t.error_description
       << ")\n\n| Source | DF | Adj SS | Adj MS | F-Value | P-Value | Significance | Contribution % |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const AnovaRow& r : t.terms) {
      md << "| " << r.source << (r.pooled ? " (pooled)" : "") << " | " << r.df << " | " << format_number(r.ss) << " | "
         << format_number(r.ms) << " | " << format_number(r.f) << " | " << format_p(r.p) << " | "
         << (r.pooled ? "" : significance_word(r.p)) << " | "
         << (r.pooled ? std::string("in Error") : format_number(100.0 * r.ss / t.total.ss, 4)) << " |\n";
    }
    md << "| Error | " << t.error.df << " | " << format_number(t.error.ss) << " | " << format_number(t.error.ms)
       << " |  |  |  | " << format_number(100.0 * t.error.ss / t.total.ss, 4) << " |\n";
    if (t.unassigned.df > 0)
      md << "| " << t.unassigned.source << " | " << t.unassigned.df << " | " << format_number(t.unassigned.ss)
         << " | " << format_number(t.unassigned.ss / t.unassigned.df) << " |  |  |  | "
         << format_number(100.0 * t.unassigned.ss / t.total.ss, 4) << " |\n";
    md << "| Total | " << t.total.df << " | " << format_number(t.total.ss) << " |  |  |  |  |  |\n\n";
    md << "R-sq of the model with every term: " << format_number(100.0 * t.r2, 5)
       << " %. Marks: ** p < 0.01 (highly significant), * p < 0.05 (significant).\n\n";
  }
  return md.str();
}

json anova_json(const std::vector<DesignAnova>& tables) {
  json out = json::object();
  for (const DesignAnova& t : tables) {
    json table = json::object();
    for (const AnovaRow& r : t.terms) {
      json row = {{"ss", r.ss}, {"df", r.df}, {"ms", json_number(r.ms)}, {"F", json_number(r.f)},
                  {"p", json_number(r.p)}, {"significance", r.pooled ? "" : significance_mark(r.p)},
                  {"contribution_pct", 100.0 * r.ss / t.total.ss},
                  {"F_crit_0.05", json_number(f_critical(0.05, r.df, t.error.df))},
                  {"F_crit_0.01", json_number(f_critical(0.01, r.df, t.error.df))}};
      if (r.pooled) row["pooled"] = true;
      table[r.source] = row;
    }
    table["error"] = {{"ss", t.error.ss}, {"df", t.error.df}, {"ms", json_number(t.error.ms)},
                      {"source", t.error_description}, {"total_ss", t.total.ss}, {"total_df", t.total.df}};
    if (t.unassigned.df > 0) {
      table["error"]["unassigned_ss"] = t.unassigned.ss;
      table["error"]["unassigned_df"] = t.unassigned.df;
    }
    out[t.response] = table;
  }
  return out;
}

std::string anova_csv(const std::vector<DesignAnova>& tables) {
  std::ostringstream csv;
  csv << "response,source,df,ss,ms,F,p,significance,pooled\n";
  auto num = [](double v) { return std::isfinite(v) ? format_double(v) : std::string(); };
  for (const DesignAnova& t : tables) {
    for (const AnovaRow& r : t.terms)
      csv << t.response << ',' << r.source << ',' << r.df << ',' << num(r.ss) << ',' << num(r.ms) << ',' << num(r.f)
          << ',' << num(r.p) << ',' << (r.pooled ? "" : significance_mark(r.p)) << ',' << (r.pooled ? 1 : 0) << '\n';
    csv << t.response << ",Error," << t.error.df << ',' << num(t.error.ss) << ',' << num(t.error.ms) << ",,,,0\n";
    if (t.unassigned.df > 0)
      csv << t.response << ",Residual (not in the error)," << t.unassigned.df << ',' << num(t.unassigned.ss) << ",,,,,0\n";
    csv << t.response << ",Total," << t.total.df << ',' << num(t.total.ss) << ",,,,,0\n";
  }
  return csv.str();
}

std::string sobol_markdown(const std::vector<SobolIndices>& indices) {
  std::ostringstream md;
  for (const SobolIndices& s : indices) {
    md << "### Sobol indices of " << s.output << " (" << s.evaluations << " model evaluations, variance "
       << format_number(s.variance) << ")\n\n| Input | S1 | S1 95% CI | ST | ST 95% CI |\n|---|---|---|---|---|\n";
    for (std::size_t j = 0; j < s.inputs.size(); ++j)
      md << "| " << s.inputs[j] << " | " << format_number(s.first[j], 4) << " | +-" << format_number(s.first_conf[j], 2)
         << " | " << format_number(s.total[j], 4) << " | +-" << format_number(s.total_conf[j], 2) << " |\n";
    md << "\n";
  }
  return md.str();
}

json sobol_json(const std::vector<SobolIndices>& indices) {
  json out = json::object();
  for (const SobolIndices& s : indices) {
    json inputs = json::object();
    for (std::size_t j = 0; j < s.inputs.size(); ++j)
      inputs[s.inputs[j]] = {{"S1", s.first[j]}, {"S1_conf", s.first_conf[j]}, {"ST", s.total[j]}, {"ST_conf", s.total_conf[j]}};
    out[s.output] = {{"variance", s.variance}, {"evaluations", s.evaluations}, {"inputs", inputs}};
  }
  return out;
}

std::string morris_markdown(const std::vector<MorrisIndices>& indices) {
  std::ostringstream md;
  for (const MorrisIndices& m : indices) {
    md << "### Morris elementary effects of " << m.output << " (" << m.evaluations
       << " model evaluations; effects per unit of the normalised range)\n\n| Input | mu | mu* | sigma |\n|---|---|---|---|\n";
    for (std::size_t j = 0; j < m.inputs.size(); ++j)
      md << "| " << m.inputs[j] << " | " << format_number(m.mu[j], 4) << " | " << format_number(m.mu_star[j], 4) << " | "
         << format_number(m.sigma[j], 4) << " |\n";
    md << "\n";
  }
  return md.str();
}

json morris_json(const std::vector<MorrisIndices>& indices) {
  json out = json::object();
  for (const MorrisIndices& m : indices) {
    json inputs = json::object();
    for (std::size_t j = 0; j < m.inputs.size(); ++j)
      inputs[m.inputs[j]] = {{"mu", m.mu[j]}, {"mu_star", m.mu_star[j]}, {"sigma", m.sigma[j]}};
    out[m.output] = {{"evaluations", m.evaluations}, {"inputs", inputs}};
  }
  return out;
}

}  // namespace demcal::surrogate
