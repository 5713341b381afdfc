#pragma once
// Spheres of a 3D DEM model, stored as contiguous arrays (one per component)
// so the force and integration loops stream through memory.
#include <cstdint>
#include <vector>

#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

struct Spheres {
  // State
  std::vector<double> x, y, z;     // centre, m
  std::vector<double> vx, vy, vz;  // velocity, m/s (at t - dt/2 between steps)
  std::vector<double> wx, wy, wz;  // angular velocity, rad/s
  // Properties
  std::vector<double> radius;   // m
  std::vector<double> mass;     // kg
  std::vector<double> inertia;  // kg m^2 (2/5 m R^2 for a solid sphere)
  std::vector<std::uint8_t> group;  // material group, picks the contact model per pair
  // 1: the sphere ignores its forces and moves at its own velocity (a grip; at
  // rest when that is zero), its spin kept as set
  std::vector<std::uint8_t> fixed;
  std::vector<std::int32_t> clump;  // the rigid clump the sphere belongs to, -1 for a free sphere
  // Stable identity: what orders pairs and keys per-contact random draws, so
  // reordering the arrays (spatial sorting, threads) changes no result.
  std::vector<std::uint32_t> id;

  std::size_t size() const { return x.size(); }
  // Adds a solid sphere of density `density_kg_m3` at rest; its id is
  // `stable_id`, or its index when none is given.
  std::size_t add_sphere(Vec3 centre_m, double radius_m, double density_kg_m3, std::uint8_t material_group,
                         std::int64_t stable_id = -1);
  Vec3 position(std::size_t i) const { return {x[i], y[i], z[i]}; }
  Vec3 velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }
  Vec3 spin(std::size_t i) const { return {wx[i], wy[i], wz[i]}; }
  void set_velocity(std::size_t i, Vec3 v) { vx[i] = v.x, vy[i] = v.y, vz[i] = v.z; }
  void set_spin(std::size_t i, Vec3 w) { wx[i] = w.x, wy[i] = w.y, wz[i] = w.z; }
  void reserve(std::size_t n);
  // Reorders every array: sphere k of the result is sphere order[k] of now.
  void permute(const std::vector<std::size_t>& order);
};

}  // namespace demcal::dem3d
