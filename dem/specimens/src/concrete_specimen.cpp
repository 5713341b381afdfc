#include "demcal/dem/concrete_specimen.hpp"

#include <cmath>

namespace demcal::dem {

AggregateSummary make_aggregate_clumps(World& world, const AggregatePlacement& placement, double density_kg_m3,
                                       double thickness_m) {
  AggregateSummary summary;
  summary.placed = static_cast<int>(placement.polygons.size());
  summary.requested = placement.requested;
  summary.area_fraction = placement.area_fraction;
  Bodies& b = world.bodies;
  std::vector<std::vector<std::size_t>> members(placement.polygons.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (std::size_t k = 0; k < placement.polygons.size(); ++k) {
      const Polygon& p = placement.polygons[k];
      if (std::hypot(b.x[i] - p.cx, b.y[i] - p.cy) > p.radius) continue;
      if (!p.contains(b.x[i], b.y[i])) continue;
      members[k].push_back(i);
      b.group[i] = kAggregateGroup;
      break;
    }
  }
  for (std::size_t k = 0; k < placement.polygons.size(); ++k) {
    if (members[k].empty()) {
      ++summary.without_disks;
      continue;
    }
    const Polygon& p = placement.polygons[k];
    double cx, cy;
    p.centroid(cx, cy);
    world.add_clump(members[k], density_kg_m3 * thickness_m * p.area(), density_kg_m3 * thickness_m * p.polar_moment(),
                    cx, cy);
    ++summary.clumps;
    summary.aggregate_disks += members[k].size();
  }
  return summary;
}

}  // namespace demcal::dem
