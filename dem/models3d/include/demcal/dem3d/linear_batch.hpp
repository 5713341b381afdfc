#pragma once
// The linear law over a block of sphere pairs in batches, as one vectorised
// loop: the geometry of fill_pair_contact (pair_contact.hpp) and the law of
// linear_shear_force (linear_contact.hpp), term for term and in the same
// order, branch-free (a pair apart computes too and its results are dropped
// by selects); then the forces go to the spheres pair by pair in pair order,
// as PairForces::set puts them. A vector lane rounds as a scalar does (the
// build forbids fused multiply-adds), so the results are the scalar loop's
// bits: only the grouping differs. The scalar loop stays the reference
// (for_sphere_pairs with LinearBase::linear_touch), and a test holds the two
// to the same bits.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "demcal/dem/select.hpp"
#include "demcal/dem3d/linear_base.hpp"
#include "demcal/dem3d/sphere_records.hpp"

namespace demcal::dem3d::linear_batch {

// Pairs per batch: full vectors, and the batch's arrays stay in the first-level cache.
constexpr std::size_t kBatch = 64;

struct Batch {
  alignas(64) double fx[kBatch];  // force on i
  alignas(64) double fy[kBatch];
  alignas(64) double fz[kBatch];
  alignas(64) double mix[kBatch];  // moment about i's centre
  alignas(64) double miy[kBatch];
  alignas(64) double miz[kBatch];
  alignas(64) double mjx[kBatch];  // about j's
  alignas(64) double mjy[kBatch];
  alignas(64) double mjz[kBatch];
};

// A sphere's record (sphere_records.hpp), read by name: the records and the
// record's first index (an index, not a pointer, so a loop over pairs
// vectorises with gathers).
struct SphereView {
  const double* __restrict records;
  std::size_t at;
  double x() const { return records[at + kRecX]; }
  double y() const { return records[at + kRecY]; }
  double z() const { return records[at + kRecZ]; }
  double r() const { return records[at + kRecRadius]; }
  double vx() const { return records[at + kRecVx]; }
  double vy() const { return records[at + kRecVy]; }
  double vz() const { return records[at + kRecVz]; }
  double wx() const { return records[at + kRecWx]; }
  double wy() const { return records[at + kRecWy]; }
  double wz() const { return records[at + kRecWz]; }
};

// A pair's contact geometry in a vectorised loop: fill_pair_contact's
// arithmetic (pair_contact.hpp), term for term, whether the spheres touch or
// not (the caller selects).
struct LaneGeometry {
  double distance2, reach;  // |d|^2 and the radii summed
  double nx, ny, nz;        // unit normal from i to j
  double overlap, arm_i, arm_j;
  double rvx, rvy, rvz;  // j's contact point's velocity relative to i's
  double psx, psy, psz;  // the contact plane's spin
};

[[gnu::always_inline]] inline LaneGeometry lane_geometry(const SphereView& i, const SphereView& j) {
  LaneGeometry g;
  const double dx = j.x() - i.x(), dy = j.y() - i.y(), dz = j.z() - i.z();
  g.reach = i.r() + j.r();
  g.distance2 = dx * dx + dy * dy + dz * dz;
  const double distance = std::sqrt(g.distance2);
  const double inverse = 1.0 / distance;
  g.nx = inverse * dx, g.ny = inverse * dy, g.nz = inverse * dz;
  g.overlap = g.reach - distance;
  g.arm_i = i.r() - 0.5 * g.overlap, g.arm_j = j.r() - 0.5 * g.overlap;
  const double ax = g.arm_i * g.nx, ay = g.arm_i * g.ny, az = g.arm_i * g.nz;  // arm_i n
  const double vix = i.vx() + (i.wy() * az - i.wz() * ay);
  const double viy = i.vy() + (i.wz() * ax - i.wx() * az);
  const double viz = i.vz() + (i.wx() * ay - i.wy() * ax);
  const double minus_arm_j = -g.arm_j;
  const double bx = minus_arm_j * g.nx, by = minus_arm_j * g.ny, bz = minus_arm_j * g.nz;  // -arm_j n
  const double vjx = j.vx() + (j.wy() * bz - j.wz() * by);
  const double vjy = j.vy() + (j.wz() * bx - j.wx() * bz);
  const double vjz = j.vz() + (j.wx() * by - j.wy() * bx);
  g.rvx = vjx - vix, g.rvy = vjy - viy, g.rvz = vjz - viz;
  const double msx = 0.5 * (i.wx() + j.wx()), msy = 0.5 * (i.wy() + j.wy()), msz = 0.5 * (i.wz() + j.wz());
  const double dvx = j.vx() - i.vx(), dvy = j.vy() - i.vy(), dvz = j.vz() - i.vz();
  const double about = msx * g.nx + msy * g.ny + msz * g.nz;
  g.psx = inverse * (g.ny * dvz - g.nz * dvy) + about * g.nx;
  g.psy = inverse * (g.nz * dvx - g.nx * dvz) + about * g.ny;
  g.psz = inverse * (g.nx * dvy - g.ny * dvx) + about * g.nz;
  return g;
}

// The contact plane's turn over a step (turned_shear's h = dt/2 times its
// spin, and Cayley's factor 2 - 2 |h|^2).
struct LaneTurn {
  double hx, hy, hz, factor;
};

[[gnu::always_inline]] inline LaneTurn lane_turn(const LaneGeometry& g, double half_dt) {
  LaneTurn t;
  t.hx = half_dt * g.psx, t.hy = half_dt * g.psy, t.hz = half_dt * g.psz;
  t.factor = 2.0 - 2.0 * (t.hx * t.hx + t.hy * t.hy + t.hz * t.hz);
  return t;
}

// incremented_shear (linear_contact.hpp) in a vectorised loop: the stored
// tangential vector s turned with the plane, what is left along the normal
// dropped, grown by stiffness_dt times the tangential part of `rate`.
[[gnu::always_inline]] inline void lane_increment(const LaneGeometry& g, const LaneTurn& t, double sx, double sy,
                                                  double sz, double rx, double ry, double rz, double stiffness_dt,
                                                  double& ox, double& oy, double& oz) {
  const double cx = sx + (t.hy * sz - t.hz * sy), cy = sy + (t.hz * sx - t.hx * sz), cz = sz + (t.hx * sy - t.hy * sx);
  const double tx = sx + t.factor * (t.hy * cz - t.hz * cy);
  const double ty = sy + t.factor * (t.hz * cx - t.hx * cz);
  const double tz = sz + t.factor * (t.hx * cy - t.hy * cx);
  const double along = tx * g.nx + ty * g.ny + tz * g.nz;
  const double rate_n = rx * g.nx + ry * g.ny + rz * g.nz;
  ox = (tx - along * g.nx) + stiffness_dt * (rx - rate_n * g.nx);
  oy = (ty - along * g.ny) + stiffness_dt * (ry - rate_n * g.ny);
  oz = (tz - along * g.nz) + stiffness_dt * (rz - rate_n * g.nz);
}

// The block's pairs [from, from + n): their shear forces and flags updated in
// the state, their forces and moments into `b` (zero for a pair apart).
inline void linear_law(PairBlock& c, const double* __restrict records, std::size_t from, std::size_t n, double dt_s,
                       Batch& __restrict b) {
  const std::int32_t* __restrict ci = c.i + from;
  const std::int32_t* __restrict cj = c.j + from;
  dem::PairFlags* __restrict flags = c.flags + from;
  const double* __restrict kn = &c.column(kKn, from);
  const double* __restrict ks = &c.column(kKs, from);
  const double* __restrict friction = &c.column(kFriction, from);
  const double* __restrict reference = &c.column(kReferenceOverlap, from);
  double* __restrict shear_x = &c.column(kShearX, from);
  double* __restrict shear_y = &c.column(kShearY, from);
  double* __restrict shear_z = &c.column(kShearZ, from);
  const double half_dt = 0.5 * dt_s;
#pragma omp simd
  for (std::size_t p = 0; p < n; ++p) {
    const SphereView i{records, kRecordSize * static_cast<std::size_t>(ci[p])};
    const SphereView j{records, kRecordSize * static_cast<std::size_t>(cj[p])};
    const LaneGeometry g = lane_geometry(i, j);
    const bool touching = g.distance2 < g.reach * g.reach;
    // linear_shear_force
    const double squeeze = g.overlap - reference[p];
    const double fn = kn[p] * (0.0 < squeeze ? squeeze : 0.0);
    double fsx, fsy, fsz;
    lane_increment(g, lane_turn(g, half_dt), shear_x[p], shear_y[p], shear_z[p], g.rvx, g.rvy, g.rvz, ks[p] * dt_s,
                   fsx, fsy, fsz);
    const double limit = friction[p] * fn, size2 = fsx * fsx + fsy * fsy + fsz * fsz;
    const double scale = dem::select(size2 > limit * limit, limit / std::sqrt(size2), 1.0);
    fsx = scale * fsx, fsy = scale * fsy, fsz = scale * fsz;
    shear_x[p] = dem::select(touching, fsx, 0.0);
    shear_y[p] = dem::select(touching, fsy, 0.0);
    shear_z[p] = dem::select(touching, fsz, 0.0);
    flags[p] = touching ? (flags[p] | dem::kTouching) : (flags[p] & ~static_cast<dem::PairFlags>(dem::kTouching));
    // linear_touch: the force on i, and the shear force's moments about both centres.
    const double ncx = g.ny * fsz - g.nz * fsy, ncy = g.nz * fsx - g.nx * fsz, ncz = g.nx * fsy - g.ny * fsx;
    b.fx[p] = dem::select(touching, fsx - fn * g.nx, 0.0);
    b.fy[p] = dem::select(touching, fsy - fn * g.ny, 0.0);
    b.fz[p] = dem::select(touching, fsz - fn * g.nz, 0.0);
    b.mix[p] = dem::select(touching, g.arm_i * ncx, 0.0);
    b.miy[p] = dem::select(touching, g.arm_i * ncy, 0.0);
    b.miz[p] = dem::select(touching, g.arm_i * ncz, 0.0);
    b.mjx[p] = dem::select(touching, g.arm_j * ncx, 0.0);
    b.mjy[p] = dem::select(touching, g.arm_j * ncy, 0.0);
    b.mjz[p] = dem::select(touching, g.arm_j * ncz, 0.0);
  }
}

// The batch's forces into `out` for the block's pairs [from, from + n), in
// pair order, as PairForces::set puts them (the pointers held in locals, so
// the stores through them do not make the loop reload them). With `touches`,
// a pair apart adds nothing to the spheres' sums (each starts at +0, which a
// zero term leaves as it is).
inline void put_batch(const PairForces& out, std::size_t from, std::size_t n, const Batch& b,
                      const std::int32_t* touches) {
  double* __restrict fx = out.fx + from;
  double* __restrict fy = out.fy + from;
  double* __restrict fz = out.fz + from;
  for (std::size_t p = 0; p < n; ++p) fx[p] = b.fx[p], fy[p] = b.fy[p], fz[p] = b.fz[p];
  if (!out.sum_fx) {
    double* __restrict mx = out.mx + 2 * from;
    double* __restrict my = out.my + 2 * from;
    double* __restrict mz = out.mz + 2 * from;
    for (std::size_t p = 0; p < n; ++p) {
      mx[2 * p] = b.mix[p], my[2 * p] = b.miy[p], mz[2 * p] = b.miz[p];
      mx[2 * p + 1] = b.mjx[p], my[2 * p + 1] = b.mjy[p], mz[2 * p + 1] = b.mjz[p];
    }
    return;
  }
  double* __restrict sum_fx = out.sum_fx;
  double* __restrict sum_fy = out.sum_fy;
  double* __restrict sum_fz = out.sum_fz;
  double* __restrict sum_mx = out.sum_mx;
  double* __restrict sum_my = out.sum_my;
  double* __restrict sum_mz = out.sum_mz;
  const std::int32_t* __restrict ci = out.i + from;
  const std::int32_t* __restrict cj = out.j + from;
  const std::size_t stride = out.sum_stride;
  for (std::size_t p = 0; p < n; ++p) {
    if (touches && !touches[p]) continue;
    const std::size_t i = static_cast<std::size_t>(ci[p]) * stride, j = static_cast<std::size_t>(cj[p]) * stride;
    sum_fx[i] += b.fx[p], sum_fy[i] += b.fy[p], sum_fz[i] += b.fz[p];
    sum_mx[i] += b.mix[p], sum_my[i] += b.miy[p], sum_mz[i] += b.miz[p];
    sum_fx[j] -= b.fx[p], sum_fy[j] -= b.fy[p], sum_fz[j] -= b.fz[p];
    sum_mx[j] += b.mjx[p], sum_my[j] += b.mjy[p], sum_mz[j] += b.mjz[p];
  }
}

// Asks for the cache lines of the block's pairs [from, from + n)'s second
// spheres' sums before the law runs, so they arrive while it computes: the
// first sphere's sums stay in cache from pair to pair (the pairs run by it),
// the second's are the misses of the scatter (half its time at 1e5 spheres).
inline void prefetch_sums(const PairForces& out, std::size_t from, std::size_t n) {
  if (!out.sum_fx) return;
  for (std::size_t p = 0; p < n; ++p)
    __builtin_prefetch(out.sum_fx + static_cast<std::size_t>(out.j[from + p]) * out.sum_stride, 1, 3);
}

// Whether each of the block's pairs [from, from + n) touches
// (fill_pair_contact's test); returns how many do. 32-bit answers: bytes
// would make the compiler take 32 pairs a vector and spill.
inline std::size_t touching(const PairBlock& c, const double* __restrict records, std::size_t from, std::size_t n,
                            std::int32_t* __restrict touches) {
  const std::int32_t* __restrict ci = c.i + from;
  const std::int32_t* __restrict cj = c.j + from;
  std::int32_t count = 0;
#pragma omp simd reduction(+ : count)
  for (std::size_t p = 0; p < n; ++p) {
    const SphereView i{records, kRecordSize * static_cast<std::size_t>(ci[p])};
    const SphereView j{records, kRecordSize * static_cast<std::size_t>(cj[p])};
    const double dx = j.x() - i.x(), dy = j.y() - i.y(), dz = j.z() - i.z();
    const double reach = i.r() + j.r();
    touches[p] = dx * dx + dy * dy + dz * dz < reach * reach;
    count += touches[p];
  }
  return static_cast<std::size_t>(count);
}

// The linear law over a whole block, its forces put pair by pair in pair
// order. A batch where no pair touches only forgets its shear forces; a pair
// apart adds nothing to the spheres' sums (each starts at +0, which a zero
// term leaves as it is), so only touching pairs are added.
inline void linear_sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) {
  std::vector<double> own;
  const double* records = step.records;
  if (!records) own = sphere_records(s), records = own.data();
  Batch b;
  alignas(64) std::int32_t touches[kBatch];
  for (std::size_t from = 0; from < c.size; from += kBatch) {
    const std::size_t n = std::min(kBatch, c.size - from);
    if (touching(c, records, from, n, touches) == 0) {
      for (std::size_t p = 0; p < n; ++p) {
        c.flags[from + p] &= ~static_cast<dem::PairFlags>(dem::kTouching);
        c.column(kShearX, from + p) = c.column(kShearY, from + p) = c.column(kShearZ, from + p) = 0.0;
      }
      if (out.sum_fx) {
        std::fill_n(out.fx + from, n, 0.0), std::fill_n(out.fy + from, n, 0.0), std::fill_n(out.fz + from, n, 0.0);
      } else {
        for (std::size_t p = 0; p < n; ++p) out.set(from + p, {}, {}, {});
      }
      continue;
    }
    prefetch_sums(out, from, n);
    linear_law(c, records, from, n, step.dt_s, b);
    put_batch(out, from, n, b, touches);
  }
}

}  // namespace demcal::dem3d::linear_batch
