#pragma once
// Turns a packed disk specimen into concrete: the disks whose centres fall
// inside a placed aggregate polygon move to the aggregate group and become
// that aggregate's rigid clump, with the mass and inertia of the polygon (a
// polygon that holds no centre takes the nearest free disk).
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/aggregates.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

constexpr std::uint8_t kAggregateGroup = 2;

struct AggregateSummary {
  int placed = 0;            // polygons placed
  int requested = 0;         // by the gradation
  int clumps = 0;            // polygons holding at least one disk
  int single_disk = 0;       // polygons holding no disk centre, given the nearest free disk
  int without_disks = 0;     // polygons with no free disk within their circle: no body
  std::size_t aggregate_disks = 0;
  double area_fraction = 0;         // placed polygon area / specimen area
  double target_area_fraction = 0;  // Walraven's P_c over the size range
};

// Disks must already be in `world` in the polygons' frame. Returns what was made.
AggregateSummary make_aggregate_clumps(World& world, const AggregatePlacement& placement, double density_kg_m3,
                                       double thickness_m);

}  // namespace demcal::dem
