#pragma once
// The linear law of one 3D contact, shared by sphere-sphere and sphere-wall
// pairs: a normal spring on the overlap, a shear force vector that turns with
// the contact plane (PFC3D: projected onto the new plane and turned by the
// pair's mean spin about the normal, its length kept), an increment ks vt dt,
// and Coulomb's limit.
#include <cmath>

#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

struct LinearContactInput {
  Vec3 normal;        // unit, from i to j (to the wall for a wall pair)
  double overlap_m;   // > 0 in contact
  double arm_i_m;     // from i's centre to the contact point along the normal
  Vec3 relative_velocity_m_s;  // of j's contact point relative to i's
  Vec3 mean_spin_rad_s;        // (w_i + w_j) / 2 (w_j = 0 for a wall)
  double kn_n_m, ks_n_m, friction, reference_overlap_m;
  double dt_s;
};

// A stored shear vector carried to the contact plane of normal `n`: projected
// onto it, turned about it by the pair's mean spin over the step, its length
// kept (first order in the step's angle; objective under a rigid rotation of
// the pair).
inline Vec3 turned_shear(Vec3 stored, Vec3 n, Vec3 mean_spin_rad_s, double dt_s) {
  const double length2 = dot(stored, stored);
  if (!(length2 > 0)) return stored;  // nothing stored (a new contact): nothing to turn
  Vec3 fs = stored - dot(stored, n) * n;
  fs = fs + (dot(mean_spin_rad_s, n) * dt_s) * cross(n, fs);
  const double turned2 = dot(fs, fs);
  return turned2 > 0 ? std::sqrt(length2 / turned2) * fs : fs;
}

// The new shear force (force on i), from the stored one; `normal_force_n` gets the normal force's size.
inline Vec3 linear_shear_force(const LinearContactInput& in, Vec3 stored, double& normal_force_n) {
  const Vec3 n = in.normal;
  normal_force_n = in.kn_n_m * std::max(0.0, in.overlap_m - in.reference_overlap_m);
  Vec3 fs = turned_shear(stored, n, in.mean_spin_rad_s, in.dt_s);
  const Vec3 vt = in.relative_velocity_m_s - dot(in.relative_velocity_m_s, n) * n;
  fs = fs + (in.ks_n_m * in.dt_s) * vt;
  // Coulomb's cap; the square root only for a sliding contact.
  const double limit = in.friction * normal_force_n, size2 = dot(fs, fs);
  if (size2 > limit * limit) fs = (limit / std::sqrt(size2)) * fs;
  return fs;
}

}  // namespace demcal::dem3d
