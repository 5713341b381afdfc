#pragma once
// The linear law of one 3D contact, shared by sphere-sphere and sphere-wall
// pairs: a normal spring on the overlap, a shear force vector that turns with
// the contact plane (PFC3D: by the turn of the normal and the pair's mean spin
// about it, its length kept), an increment ks vt dt, and Coulomb's limit.
#include <cmath>

#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

struct LinearContactInput {
  Vec3 normal;        // unit, from i to j (to the wall for a wall pair)
  double overlap_m;   // > 0 in contact
  double arm_i_m;     // from i's centre to the contact point along the normal
  Vec3 relative_velocity_m_s;  // of j's contact point relative to i's
  Vec3 plane_spin_rad_s;       // the contact plane's spin (PairContact)
  double kn_n_m, ks_n_m, friction, reference_overlap_m;
  double dt_s;
};

// A stored shear vector carried to the contact plane of normal `n`: turned
// by the plane's spin over the step (the normal's turn, and the pair's mean
// spin about the normal) as a rotation (Cayley's form, its factor 2 / (1 +
// h^2) taken to second order: orthogonal to 1e-16 at the steps' angles, no
// trigonometry, no division), then what is left along the normal dropped
// (a length change of the fourth order in the step's angle). Under a rigid
// rotation of the pair it turns with the pair. (Projecting onto the new
// plane and restoring the length, as LAMMPS does, grows a component across
// the plane's turn by the square of the step's angle every step.)
inline Vec3 turned_shear(Vec3 stored, Vec3 n, Vec3 plane_spin_rad_s, double dt_s) {
  const Vec3 h = (0.5 * dt_s) * plane_spin_rad_s;
  const Vec3 fs = stored + (2.0 - 2.0 * dot(h, h)) * cross(h, stored + cross(h, stored));
  return fs - dot(fs, n) * n;
}

// A stored tangential vector (a shear force on i, a bending moment on i)
// carried to the contact plane of normal `n` and grown by `stiffness_dt`
// times the tangential part of `relative_rate` (j's relative to i's: a
// velocity, or a spin for a bending moment). No limit.
inline Vec3 incremented_shear(Vec3 stored, Vec3 n, Vec3 plane_spin_rad_s, double dt_s, Vec3 relative_rate,
                              double stiffness_dt) {
  const Vec3 fs = turned_shear(stored, n, plane_spin_rad_s, dt_s);
  const Vec3 vt = relative_rate - dot(relative_rate, n) * n;
  return fs + stiffness_dt * vt;
}

// The new shear force (force on i), from the stored one; `normal_force_n` gets the normal force's size.
inline Vec3 linear_shear_force(const LinearContactInput& in, Vec3 stored, double& normal_force_n) {
  const Vec3 n = in.normal;
  normal_force_n = in.kn_n_m * std::max(0.0, in.overlap_m - in.reference_overlap_m);
  Vec3 fs = incremented_shear(stored, n, in.plane_spin_rad_s, in.dt_s, in.relative_velocity_m_s, in.ks_n_m * in.dt_s);
  // Coulomb's cap; the square root only for a sliding contact.
  const double limit = in.friction * normal_force_n, size2 = dot(fs, fs);
  if (size2 > limit * limit) fs = (limit / std::sqrt(size2)) * fs;
  return fs;
}

}  // namespace demcal::dem3d
