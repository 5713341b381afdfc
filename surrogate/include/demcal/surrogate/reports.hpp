#pragma once
// Tables of the analysis stage as Markdown (for people, laid out like
// Minitab's), JSON (for the pipeline and the plot scripts) and CSV.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/surrogate/design_anova.hpp"
#include "demcal/surrogate/gabp.hpp"
#include "demcal/surrogate/range_analysis.hpp"
#include "demcal/surrogate/response_surface.hpp"
#include "demcal/surrogate/sensitivity.hpp"

namespace demcal::surrogate {

// Numbers as printed in the Markdown tables: `significant` digits; p-values
// with four decimals.
std::string format_number(double value, int significant = 6);
std::string format_p(double p);

std::string range_markdown(const std::vector<RangeAnalysis>& analyses);
nlohmann::json range_json(const std::vector<RangeAnalysis>& analyses);
std::string range_csv(const std::vector<RangeAnalysis>& analyses);

std::string anova_markdown(const std::vector<DesignAnova>& tables);
// {"<response>": {"<factor>": {"ss","df","ms","F","p","significance","pooled","contribution_pct"}, "error": {"ss","df","ms"}}}
nlohmann::json anova_json(const std::vector<DesignAnova>& tables);
std::string anova_csv(const std::vector<DesignAnova>& tables);

std::string surface_markdown(const SurfaceFit& fit);
std::string gabp_markdown(const GabpFit& fit);

std::string sobol_markdown(const std::vector<SobolIndices>& indices);
nlohmann::json sobol_json(const std::vector<SobolIndices>& indices);
std::string morris_markdown(const std::vector<MorrisIndices>& indices);
nlohmann::json morris_json(const std::vector<MorrisIndices>& indices);

}  // namespace demcal::surrogate
