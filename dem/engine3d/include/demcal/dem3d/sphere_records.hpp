#pragma once
// Each sphere's centre, radius, velocity and spin side by side, ten doubles
// a sphere: a vectorised pair law gathers a pair's two spheres from two
// records (two or three cache lines) instead of from ten arrays each, which
// at 1e5 spheres, beyond the second-level cache, was most of its time. The
// world refreshes them before each step's forces (StepContext::records); a
// model called without them packs its own.
#include <cstddef>
#include <vector>

#include "demcal/dem3d/spheres.hpp"

namespace demcal::dem3d {

enum SphereRecordField : std::size_t { kRecX, kRecY, kRecZ, kRecRadius, kRecVx, kRecVy, kRecVz, kRecWx, kRecWy, kRecWz,
                                       kRecordSize };

// Spheres [from, to) into `records` (kRecordSize values a sphere, from sphere 0).
inline void pack_sphere_records(const Spheres& s, std::size_t from, std::size_t to, double* records) {
  for (std::size_t i = from; i < to; ++i) {
    double* r = records + kRecordSize * i;
    r[kRecX] = s.x[i], r[kRecY] = s.y[i], r[kRecZ] = s.z[i], r[kRecRadius] = s.radius[i];
    r[kRecVx] = s.vx[i], r[kRecVy] = s.vy[i], r[kRecVz] = s.vz[i];
    r[kRecWx] = s.wx[i], r[kRecWy] = s.wy[i], r[kRecWz] = s.wz[i];
  }
}

inline std::vector<double> sphere_records(const Spheres& s) {
  std::vector<double> records(kRecordSize * s.size());
  pack_sphere_records(s, 0, s.size(), records.data());
  return records;
}

}  // namespace demcal::dem3d
