#pragma once
// The linear contact law with Coulomb friction, shared by every model that
// falls back to it (a broken bond behaves as a linear contact). Its state
// columns come first in every model built on it (LinearBase).
#include <algorithm>
#include <cmath>

#include "demcal/dem/contact_geometry.hpp"
#include "demcal/dem/pair_batch.hpp"

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
//
// Whether a bonded pair is short of its reference, and whether a contact with
// little normal force slides, change from step to step with the specimen's
// vibration: branches on them were mispredicted on a third of the pairs, so
// the law selects with max and min instead (the same values; a zero shear
// force is now always +0, where a capped one could be -0).
inline PairForce linear_force(const PairBlock& c, std::size_t k, const Geometry& g, double dt) {
  const PairState<double> s = c.column.pair(k);
  const double overlap = g.overlap - s[kReferenceOverlap];
  const bool touching = overlap > 0;
  // max(0, overlap) is +0 for a pair apart (also at overlap -0).
  const double fn = s[kNormalStiffness] * std::max(0.0, overlap);
  const double limit = s[kFriction] * fn;
  const double trial = s[kShearForce] - s[kShearStiffness] * g.vs * dt;
  // The Coulomb cap; apart, the limit is 0 and the cap leaves +-0, which
  // adding +0 makes +0, the released contact's shear.
  const double fs = std::min(std::max(trial, -limit), limit) + 0.0;
  s[kShearForce] = fs;
  c.flags[k] = (c.flags[k] & ~static_cast<PairFlags>(kTouching)) | (touching ? kTouching : 0u);
  PairForce f;
  f.fn = fn;
  f.fs = fs;
  return f;
}

// The linear law for lane p of a batch loop (pair_batch.hpp), `s` the batch's
// state: linear_force's arithmetic, term for term, with selects for its max
// and min and without its stores, so a loop of it vectorises. The caller
// stores the shear force and the flags.
struct LinearLane {
  double fn, fs;  // N
  bool touching;  // past the reference overlap
};

inline LinearLane linear_lane(const StateColumns<double>& s, std::size_t p, double overlap_m, double vs_m_s,
                              double dt) {
  const double overlap = overlap_m - s(kReferenceOverlap, p);
  LinearLane l;
  l.touching = overlap > 0;
  l.fn = s(kNormalStiffness, p) * select(0.0 < overlap, overlap, 0.0);           // std::max(0.0, overlap)
  const double limit = s(kFriction, p) * l.fn;
  const double trial = s(kShearForce, p) - s(kShearStiffness, p) * vs_m_s * dt;
  const double capped_below = select(trial < -limit, -limit, trial);              // std::max(trial, -limit)
  l.fs = select(limit < capped_below, limit, capped_below) + 0.0;                 // std::min(.., limit)
  return l;
}

// Pair p's force as for_disk_pairs turns a PairForce into one, into the batch
// (zero for a pair skipped this step).
inline void batch_force(ForceBatch& __restrict f, std::size_t p, const GeometryBatch& __restrict g, bool skipped,
                        double fn, double fs, double moment) {
  const double fx = fn * g.nx[p] - fs * g.ny[p];
  const double fy = fn * g.ny[p] + fs * g.nx[p];
  f.fx[p] = select(skipped, 0.0, fx);
  f.fy[p] = select(skipped, 0.0, fy);
  f.moment_i[p] = select(skipped, 0.0, -g.arm_i[p] * fs - moment);
  f.moment_j[p] = select(skipped, 0.0, -g.arm_j[p] * fs + moment);
}

}  // namespace demcal::dem
