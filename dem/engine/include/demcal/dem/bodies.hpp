#pragma once
// Disks of a 2D DEM model, stored as contiguous arrays (one per quantity) so
// the force and integration loops stream through memory.
#include <cstdint>
#include <vector>

namespace demcal::dem {

struct Bodies {
  // State
  std::vector<double> x, y;      // centre, m
  std::vector<double> vx, vy;    // velocity, m/s (at t - dt/2 between steps)
  std::vector<double> w;         // angular velocity, rad/s
  // Force accumulators for the current step
  std::vector<double> fx, fy;    // N
  std::vector<double> moment;    // N m
  // Properties
  std::vector<double> radius;    // m
  std::vector<double> mass;      // kg (density scaling may raise it)
  std::vector<double> inertia;   // kg m^2
  std::vector<std::uint8_t> group;  // material group, picks the contact model per pair
  std::vector<std::uint8_t> fixed;  // 1: the disk does not move
  std::vector<std::int32_t> clump;  // rigid clump the disk belongs to, -1 for a free disk
  // Stable identity: what orders pairs and keys per-contact random draws, so
  // reordering the arrays (spatial sorting, threads) changes no result. A
  // specimen's disks keep their index in the packed specimen.
  std::vector<std::uint32_t> id;

  std::size_t size() const { return x.size(); }
  // Adds a disk of density `density_kg_m3` and thickness `thickness_m` at
  // rest; its id is `stable_id`, or its index when none is given.
  std::size_t add_disk(double x_m, double y_m, double radius_m, double density_kg_m3, double thickness_m,
                       std::uint8_t material_group, std::int64_t stable_id = -1);
  void clear_forces();
  void reserve(std::size_t n);
};

}  // namespace demcal::dem
