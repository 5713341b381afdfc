#pragma once
// What every 3D contact model needs of a touching pair, computed one way for
// all of them: the unit normal from i to j (to the wall), the overlap, the
// arms from each centre to the contact point (the middle of the overlap), the
// velocity of j's contact point relative to i's (spins included), and the
// spin of the contact plane over the step: the normal's own turn (the centres'
// relative motion across it) plus the pair's mean spin about the normal (a
// wall's side spins not: half of i's; a wall's normal is taken as fixed).
#include <cmath>
#include <cstddef>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/spheres.hpp"

namespace demcal::dem3d {

struct PairContact {
  Vec3 normal;
  double overlap_m = 0, arm_i_m = 0, arm_j_m = 0;
  Vec3 relative_velocity_m_s, plane_spin_rad_s;
};

// The geometry of spheres i and j at centre offset d (j - i), |d|^2 = distance2.
inline void fill_pair_contact(const Spheres& s, std::size_t i, std::size_t j, Vec3 d, double reach, double distance2,
                              PairContact& c) {
  const double distance = std::sqrt(distance2);
  c.normal = (1.0 / distance) * d;
  c.overlap_m = reach - distance;
  c.arm_i_m = s.radius[i] - 0.5 * c.overlap_m;
  c.arm_j_m = s.radius[j] - 0.5 * c.overlap_m;
  const Vec3 vi = s.velocity(i) + cross(s.spin(i), c.arm_i_m * c.normal);
  const Vec3 vj = s.velocity(j) + cross(s.spin(j), -c.arm_j_m * c.normal);
  c.relative_velocity_m_s = vj - vi;
  const Vec3 mean_spin = 0.5 * (s.spin(i) + s.spin(j));
  c.plane_spin_rad_s = (1.0 / distance) * cross(c.normal, s.velocity(j) - s.velocity(i)) + dot(mean_spin, c.normal) * c.normal;
}

// Spheres i and j; false when they are apart.
inline bool sphere_pair_contact(const Spheres& s, std::size_t i, std::size_t j, PairContact& c) {
  const Vec3 d = s.position(j) - s.position(i);
  const double reach = s.radius[i] + s.radius[j], distance2 = dot(d, d);
  if (!(distance2 < reach * reach)) return false;
  fill_pair_contact(s, i, j, d, reach, distance2, c);
  return true;
}

// Spheres i and j touching or not (a bond holds them across a gap): the
// overlap is negative across a gap and the contact point lies in its middle.
inline void sphere_pair_geometry(const Spheres& s, std::size_t i, std::size_t j, PairContact& c) {
  const Vec3 d = s.position(j) - s.position(i);
  fill_pair_contact(s, i, j, d, s.radius[i] + s.radius[j], dot(d, d), c);
}

// Sphere i against the wall of geometry g's pair k (block-local), touching
// or not (an adhesive contact holds across a gap).
inline void wall_pair_geometry(const Spheres& s, std::size_t i, const WallGeometry& g, std::size_t k, PairContact& c) {
  c.overlap_m = g.overlap_m[k];
  c.normal = {g.nx[k], g.ny[k], g.nz[k]};
  c.arm_i_m = s.radius[i] - 0.5 * c.overlap_m;
  c.arm_j_m = 0.0;
  const Vec3 vi = s.velocity(i) + cross(s.spin(i), c.arm_i_m * c.normal);
  c.relative_velocity_m_s = Vec3{g.vx[k], g.vy[k], g.vz[k]} - vi;
  c.plane_spin_rad_s = (0.5 * dot(s.spin(i), c.normal)) * c.normal;
}

// The same; false when apart.
inline bool wall_pair_contact(const Spheres& s, std::size_t i, const WallGeometry& g, std::size_t k, PairContact& c) {
  if (!(g.overlap_m[k] > 0)) return false;
  wall_pair_geometry(s, i, g, k, c);
  return true;
}

// A model's loops over a block: `touch(k, contact)` for each touching pair,
// `leave(k)` for each pair apart.
template <class Touch, class Leave>
inline void for_sphere_pairs(const PairBlock& c, const Spheres& s, Touch touch, Leave leave) {
  PairContact p;
  for (std::size_t k = 0; k < c.size; ++k)
    if (sphere_pair_contact(s, static_cast<std::size_t>(c.i[k]), static_cast<std::size_t>(c.j[k]), p))
      touch(k, p);
    else
      leave(k);
}

template <class Touch, class Leave>
inline void for_wall_pairs(const PairBlock& c, const Spheres& s, const WallGeometry& g, Touch touch, Leave leave) {
  PairContact p;
  for (std::size_t k = 0; k < c.size; ++k)
    if (wall_pair_contact(s, static_cast<std::size_t>(c.i[k]), g, k, p))
      touch(k, p);
    else
      leave(k);
}

}  // namespace demcal::dem3d
