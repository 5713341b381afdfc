#include "demcal/doe/design_kinds.hpp"

#include "demcal/core/error.hpp"

namespace demcal::doe {

const std::vector<DesignKind>& design_kinds() {
  static const std::vector<DesignKind> kinds = {
      {"oa", "orthogonal-array", "orthogonal array (Rao-Hamming/Bose over GF(q), L18, L36, collapsed 3-level plans)", 1, 0,
       {"--runs", "--levels", "--blank", "--doubled-level"}, "--runs"},
      {"fullfact", "full factorial", "full factorial", 1, 0, {"--levels"},
       "product of the level counts (at most 1,000,000)", 0, 1000000},
      {"fracfact", "fractional factorial", "2-level fractional factorial of maximal resolution", 2, 25, {"--runs", "--generators"},
       "--runs (a power of two) or 2^(factors - generators)"},
      {"pb", "Plackett-Burman", "Plackett-Burman screening design", 1, 0, {"--runs"}, "--runs, default the smallest above the factor count"},
      {"ccd", "central composite", "central composite (circumscribed, inscribed, face-centred)", 2, 10, {"--alpha", "--center", "--type"},
       "2^k + 2k + centre points (Minitab's defaults)"},
      {"bbd", "Box-Behnken", "Box-Behnken (BIBD for 6 and 7 factors)", 3, 7, {"--center"},
       "15, 27, 46, 54, 62 for 3..7 factors with Minitab's centre points"},
      {"lhs", "Latin hypercube", "Latin hypercube (random, centred, maximin, phi_p by ESE)", 1, 0, {"--runs", "--criterion", "--iterations"},
       "--runs (at least 2)", 2},
      {"sobol", "Sobol", "Owen-scrambled Sobol sequence", 1, 3667, {"--runs"}, "--runs (at least 2)", 2},
  };
  return kinds;
}

const DesignKind& find_design_kind(const std::string& name) {
  for (const DesignKind& k : design_kinds())
    if (k.name == name) return k;
  std::string list;
  for (const DesignKind& k : design_kinds()) list += (list.empty() ? "" : ", ") + k.name;
  throw Error("unknown design kind \"" + name + "\" (expected " + list + ")");
}

nlohmann::json design_kinds_json() {
  nlohmann::json kinds = nlohmann::json::object();
  for (const DesignKind& k : design_kinds())
    kinds[k.name] = {{"title", k.title},
                     {"description", k.description},
                     {"min_factors", k.min_factors},
                     {"max_factors", k.max_factors > 0 ? nlohmann::json(k.max_factors) : nlohmann::json()},
                     {"min_runs", k.min_runs > 0 ? nlohmann::json(k.min_runs) : nlohmann::json()},
                     {"max_runs", k.max_runs > 0 ? nlohmann::json(k.max_runs) : nlohmann::json()},
                     {"options", k.options},
                     {"runs", k.runs}};
  return {{"kinds", kinds}};
}

}  // namespace demcal::doe
