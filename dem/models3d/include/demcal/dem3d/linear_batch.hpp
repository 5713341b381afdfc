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

#include "demcal/dem/select.hpp"
#include "demcal/dem3d/linear_base.hpp"

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

// The block's pairs [from, from + n): their shear forces and flags updated in
// the state, their forces and moments into `b` (zero for a pair apart).
inline void linear_law(PairBlock& c, const Spheres& s, std::size_t from, std::size_t n, double dt_s,
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
  const double* __restrict x = s.x.data();
  const double* __restrict y = s.y.data();
  const double* __restrict z = s.z.data();
  const double* __restrict r = s.radius.data();
  const double* __restrict vx = s.vx.data();
  const double* __restrict vy = s.vy.data();
  const double* __restrict vz = s.vz.data();
  const double* __restrict wx = s.wx.data();
  const double* __restrict wy = s.wy.data();
  const double* __restrict wz = s.wz.data();
  const double half_dt = 0.5 * dt_s;
#pragma omp simd
  for (std::size_t p = 0; p < n; ++p) {
    const std::int32_t i = ci[p], j = cj[p];
    // fill_pair_contact
    const double dx = x[j] - x[i], dy = y[j] - y[i], dz = z[j] - z[i];
    const double reach = r[i] + r[j], distance2 = dx * dx + dy * dy + dz * dz;
    const bool touching = distance2 < reach * reach;
    const double distance = std::sqrt(distance2);
    const double inverse = 1.0 / distance;
    const double nx = inverse * dx, ny = inverse * dy, nz = inverse * dz;
    const double overlap = reach - distance;
    const double arm_i = r[i] - 0.5 * overlap, arm_j = r[j] - 0.5 * overlap;
    const double ax = arm_i * nx, ay = arm_i * ny, az = arm_i * nz;  // arm_i n
    const double vix = vx[i] + (wy[i] * az - wz[i] * ay);
    const double viy = vy[i] + (wz[i] * ax - wx[i] * az);
    const double viz = vz[i] + (wx[i] * ay - wy[i] * ax);
    const double minus_arm_j = -arm_j;
    const double bx = minus_arm_j * nx, by = minus_arm_j * ny, bz = minus_arm_j * nz;  // -arm_j n
    const double vjx = vx[j] + (wy[j] * bz - wz[j] * by);
    const double vjy = vy[j] + (wz[j] * bx - wx[j] * bz);
    const double vjz = vz[j] + (wx[j] * by - wy[j] * bx);
    const double rvx = vjx - vix, rvy = vjy - viy, rvz = vjz - viz;
    const double msx = 0.5 * (wx[i] + wx[j]), msy = 0.5 * (wy[i] + wy[j]), msz = 0.5 * (wz[i] + wz[j]);
    const double dvx = vx[j] - vx[i], dvy = vy[j] - vy[i], dvz = vz[j] - vz[i];
    const double turn_x = inverse * (ny * dvz - nz * dvy);
    const double turn_y = inverse * (nz * dvx - nx * dvz);
    const double turn_z = inverse * (nx * dvy - ny * dvx);
    const double about = msx * nx + msy * ny + msz * nz;
    const double psx = turn_x + about * nx, psy = turn_y + about * ny, psz = turn_z + about * nz;
    // linear_shear_force
    const double squeeze = overlap - reference[p];
    const double fn = kn[p] * (0.0 < squeeze ? squeeze : 0.0);
    const double hx = half_dt * psx, hy = half_dt * psy, hz = half_dt * psz;
    const double sx = shear_x[p], sy = shear_y[p], sz = shear_z[p];
    const double cx = sx + (hy * sz - hz * sy), cy = sy + (hz * sx - hx * sz), cz = sz + (hx * sy - hy * sx);
    const double factor = 2.0 - 2.0 * (hx * hx + hy * hy + hz * hz);
    const double tx = sx + factor * (hy * cz - hz * cy);
    const double ty = sy + factor * (hz * cx - hx * cz);
    const double tz = sz + factor * (hx * cy - hy * cx);
    const double along = tx * nx + ty * ny + tz * nz;
    const double ux = tx - along * nx, uy = ty - along * ny, uz = tz - along * nz;
    const double rv_n = rvx * nx + rvy * ny + rvz * nz;
    const double vtx = rvx - rv_n * nx, vty = rvy - rv_n * ny, vtz = rvz - rv_n * nz;
    const double stiffness_dt = ks[p] * dt_s;
    double fsx = ux + stiffness_dt * vtx, fsy = uy + stiffness_dt * vty, fsz = uz + stiffness_dt * vtz;
    const double limit = friction[p] * fn, size2 = fsx * fsx + fsy * fsy + fsz * fsz;
    const double scale = dem::select(size2 > limit * limit, limit / std::sqrt(size2), 1.0);
    fsx = scale * fsx, fsy = scale * fsy, fsz = scale * fsz;
    shear_x[p] = dem::select(touching, fsx, 0.0);
    shear_y[p] = dem::select(touching, fsy, 0.0);
    shear_z[p] = dem::select(touching, fsz, 0.0);
    flags[p] = touching ? (flags[p] | dem::kTouching) : (flags[p] & ~static_cast<dem::PairFlags>(dem::kTouching));
    // linear_touch: the force on i, and the shear force's moments about both centres.
    const double ncx = ny * fsz - nz * fsy, ncy = nz * fsx - nx * fsz, ncz = nx * fsy - ny * fsx;
    b.fx[p] = dem::select(touching, fsx - fn * nx, 0.0);
    b.fy[p] = dem::select(touching, fsy - fn * ny, 0.0);
    b.fz[p] = dem::select(touching, fsz - fn * nz, 0.0);
    b.mix[p] = dem::select(touching, arm_i * ncx, 0.0);
    b.miy[p] = dem::select(touching, arm_i * ncy, 0.0);
    b.miz[p] = dem::select(touching, arm_i * ncz, 0.0);
    b.mjx[p] = dem::select(touching, arm_j * ncx, 0.0);
    b.mjy[p] = dem::select(touching, arm_j * ncy, 0.0);
    b.mjz[p] = dem::select(touching, arm_j * ncz, 0.0);
  }
}

// Whether each of the block's pairs [from, from + n) touches
// (fill_pair_contact's test); returns how many do.
inline std::size_t touching(const PairBlock& c, const Spheres& s, std::size_t from, std::size_t n,
                            std::uint8_t* __restrict touches) {
  const std::int32_t* __restrict ci = c.i + from;
  const std::int32_t* __restrict cj = c.j + from;
  const double* __restrict x = s.x.data();
  const double* __restrict y = s.y.data();
  const double* __restrict z = s.z.data();
  const double* __restrict r = s.radius.data();
  std::size_t count = 0;
#pragma omp simd reduction(+ : count)
  for (std::size_t p = 0; p < n; ++p) {
    const std::int32_t i = ci[p], j = cj[p];
    const double dx = x[j] - x[i], dy = y[j] - y[i], dz = z[j] - z[i];
    const double reach = r[i] + r[j];
    touches[p] = dx * dx + dy * dy + dz * dz < reach * reach;
    count += touches[p];
  }
  return count;
}

// The linear law over a whole block, its forces put pair by pair in pair
// order. A batch where no pair touches only forgets its shear forces; a pair
// apart adds nothing to the spheres' sums (each starts at +0, which a zero
// term leaves as it is), so only touching pairs are added.
inline void linear_sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, double dt_s) {
  Batch b;
  alignas(64) std::uint8_t touches[kBatch];
  for (std::size_t from = 0; from < c.size; from += kBatch) {
    const std::size_t n = std::min(kBatch, c.size - from);
    if (touching(c, s, from, n, touches) == 0) {
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
    linear_law(c, s, from, n, dt_s, b);
    for (std::size_t p = 0; p < n; ++p) {
      if (out.sum_fx && !touches[p]) {
        out.fx[from + p] = out.fy[from + p] = out.fz[from + p] = 0.0;
        continue;
      }
      out.set(from + p, {b.fx[p], b.fy[p], b.fz[p]}, {b.mix[p], b.miy[p], b.miz[p]}, {b.mjx[p], b.mjy[p], b.mjz[p]});
    }
  }
}

}  // namespace demcal::dem3d::linear_batch
