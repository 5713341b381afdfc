#include "demcal/dem/concrete_specimen.hpp"

#include <cmath>

namespace demcal::dem {

AggregateSummary make_aggregate_clumps(World& world, const AggregatePlacement& placement, double density_kg_m3,
                                       double thickness_m) {
  AggregateSummary summary;
  summary.placed = static_cast<int>(placement.polygons.size());
  summary.requested = placement.requested;
  summary.area_fraction = placement.area_fraction;
  summary.target_area_fraction = placement.target_area_fraction;
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
  // A small polygon may hold no disk centre: it takes the free disk nearest
  // its centroid (within its bounding circle), so the aggregate's area and
  // mass are not lost to the mortar.
  for (std::size_t k = 0; k < placement.polygons.size(); ++k) {
    if (!members[k].empty()) continue;
    const Polygon& p = placement.polygons[k];
    double cx, cy;
    p.centroid(cx, cy);
    std::size_t nearest = b.size();
    double best = p.radius;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.group[i] == kAggregateGroup) continue;
      const double d = std::hypot(b.x[i] - cx, b.y[i] - cy);
      if (d <= best) {
        best = d;
        nearest = i;
      }
    }
    if (nearest == b.size()) continue;
    members[k].push_back(nearest);
    b.group[nearest] = kAggregateGroup;
    ++summary.single_disk;
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
