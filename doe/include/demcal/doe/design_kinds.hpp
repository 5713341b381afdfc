#pragma once
// The design kinds demcal-doe makes, with the options each understands and
// the factor counts it accepts: one table that the executable checks against
// and prints (demcal-doe --list-kinds), so the study layer keeps no copy.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace demcal::doe {

struct DesignKind {
  std::string name, title, description;  // title: "Box-Behnken", for messages
  int min_factors = 1;
  int max_factors = 0;  // 0: no fixed limit (the run count bounds it)
  std::vector<std::string> options;  // command-line options that apply
  std::string runs;     // how many runs it makes
  int min_runs = 0, max_runs = 0;  // limits of --runs or of the run count; 0: set by the factors alone
};

const std::vector<DesignKind>& design_kinds();
// Throws "unknown design kind "X" (expected oa, ...)".
const DesignKind& find_design_kind(const std::string& name);
// {"kinds": {name: {title, description, min_factors, max_factors, min_runs, max_runs (null: no fixed
// limit), options, runs}}}
nlohmann::json design_kinds_json();

}  // namespace demcal::doe
