#pragma once
// The linear contact law with Coulomb friction, shared by every model that
// falls back to it (a broken bond behaves as a linear contact). Its state
// columns come first in every model built on it (LinearBase).
#include <cmath>

#include "demcal/dem/contact_geometry.hpp"

namespace demcal::dem {

enum LinearColumn : std::size_t {
  kNormalStiffness = 0,  // kn, N/m
  kShearStiffness,       // ks, N/m
  kFriction,             // mu
  kShearForce,           // along t = (-n_y, n_x), N
  kReferenceOverlap,     // overlap at which the contact is force-free (PFC: -rgap), m
  kLinearColumns
};

// Deformability method (PFC): kn = A E_c / L with A = 2 r t, r the smaller
// radius and L = r_i + r_j for two disks; r = L = the disk radius for a wall.
inline double deformability_kn(double modulus_pa, double radius_i_m, double radius_j_m, bool wall, double thickness_m) {
  double r = wall ? radius_i_m : std::min(radius_i_m, radius_j_m);
  double length = wall ? radius_i_m : radius_i_m + radius_j_m;
  return 2.0 * r * thickness_m * modulus_pa / length;
}

inline void release(const PairBlock& c, std::size_t k) {
  c.column[kShearForce][k] = 0.0;
  c.flags[k] &= ~static_cast<PairFlags>(kTouching);
}

// Skip rule of unbonded contacts: a pair that does not reach its reference
// overlap (zero unless genesis set one) carries nothing this step.
inline bool skip_apart(const PairBlock& c, std::size_t k, double gap) {
  if (gap + c.column[kReferenceOverlap][k] < 0) return false;
  release(c, k);
  return true;
}

// Normal force kn * (overlap - reference), shear force updated incrementally
// and capped at mu * fn. The reference overlap (PFC's reference gap, g_r =
// -reference) is zero for a contact that formed during the test; genesis sets
// it to the overlap a pair has when the specimen is bonded, so the packing
// starts force-free whatever stiffness the test gives it, and a contact bond
// keeps the overlap it was glued at after it breaks. Pairs short of the
// reference carry no force and forget their shear.
inline PairForce linear_force(const PairBlock& c, std::size_t k, const Geometry& g, double dt) {
  PairForce f;
  const double overlap = g.overlap - c.column[kReferenceOverlap][k];
  if (overlap <= 0) {
    release(c, k);
    return f;
  }
  c.flags[k] |= kTouching;
  f.fn = c.column[kNormalStiffness][k] * overlap;
  double fs = c.column[kShearForce][k] - c.column[kShearStiffness][k] * g.vs * dt;
  const double limit = c.column[kFriction][k] * f.fn;
  if (std::abs(fs) > limit) fs = std::copysign(limit, fs);
  c.column[kShearForce][k] = fs;
  f.fs = fs;
  return f;
}

}  // namespace demcal::dem
