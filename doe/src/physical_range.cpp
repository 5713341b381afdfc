#include "demcal/doe/physical_range.hpp"

#include "demcal/core/number_format.hpp"
#include "demcal/core/units.hpp"

namespace demcal::doe {

namespace {

// The bound below which a value of `p` means nothing physically, and why.
bool lower_bound_of(const Parameter& p, double& bound, std::string& why) {
  const Quantity q = quantity_of_unit(p.unit.empty() ? "1" : p.unit, "parameter " + p.name);
  switch (q) {
    case Quantity::Stress: why = "a stress cannot be negative"; break;
    case Quantity::Stiffness: why = "a stiffness cannot be negative"; break;
    case Quantity::Length: why = "a length cannot be negative"; break;
    case Quantity::Density: why = "a density cannot be negative"; break;
    case Quantity::Time: why = "a time cannot be negative"; break;
    case Quantity::Dimensionless:
    case Quantity::Angle:
      if (p.low < 0) return false;
      why = "its range in the space is non-negative";
      break;
    default: return false;
  }
  bound = 0.0;
  return true;
}

}  // namespace

std::vector<std::string> physical_range_problems(const Table& design, const ParameterSpace& space,
                                                 const std::map<std::string, PhysicalBounds>& scene_bounds) {
  std::vector<std::string> problems;
  for (const Parameter& p : space.parameters()) {
    if (!design.has_column(p.name)) continue;
    const std::vector<double>& values = design.column(p.name);
    double low = -1e300, high = 1e300;
    std::string why_low, why_high;
    double unit_bound = 0;
    if (lower_bound_of(p, unit_bound, why_low)) low = unit_bound;
    const auto scene = scene_bounds.find(p.name);
    if (scene != scene_bounds.end()) {
      if (scene->second.low > low) {
        low = scene->second.low;
        why_low = "the scene's physical low";
      }
      if (scene->second.high < high) {
        high = scene->second.high;
        why_high = "the scene's physical high";
      }
    }
    std::size_t worst = values.size();
    double excess = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double over = std::max(low - values[i], values[i] - high);
      if (over > excess) {
        excess = over;
        worst = i;
      }
    }
    if (worst == values.size()) continue;
    const double v = values[worst];
    const bool below = v < low;
    problems.push_back(p.name + " = " + format_double(v) + " at run " + std::to_string(design.run_ids()[worst]) +
                       " is " + (below ? "below " + format_double(low) + " (" + why_low + ")"
                                       : "above " + format_double(high) + " (" + why_high + ")"));
  }
  return problems;
}

}  // namespace demcal::doe
