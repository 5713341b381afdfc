#pragma once
// The geometry shared by all contact models: overlap, normal, relative
// velocity at the contact point, and how a contact force acts on the two
// bodies. Models supply only their force law; these loops are templates so
// the law is inlined into them.
//
// Sign conventions (2D): n is the unit normal from i to j (from the wall to
// the disk for walls), t = (-n_y, n_x). The force on j (the disk, for walls)
// is fn n + fs t, fn > 0 pushing the bodies apart; i gets the opposite. vn > 0
// when the bodies separate, vs is the sliding velocity of j relative to i
// along t. `moment` is an extra couple on j (and -moment on i), for bonds.
#include <cmath>

#include "demcal/dem/bodies.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/contacts.hpp"
#include "demcal/dem/walls.hpp"

namespace demcal::dem {

// A pair's centre distance and overlap (> 0 when touching), m, computed one
// way everywhere: the force loops, the batches, a bond's installation, the
// walls made force-free, the equilibrium measure and a bond's utilisation must
// agree to the bit (a contact installed force-free is then exactly force-free).
inline double centre_distance_m(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }
inline double disk_overlap_m(double radius_i_m, double radius_j_m, double distance_m) {
  return radius_i_m + radius_j_m - distance_m;
}
inline double wall_overlap_m(double radius_m, double distance_m) { return radius_m - distance_m; }


struct Geometry {
  double nx, ny;
  double overlap;        // > 0 when touching, m
  double vn, vs;         // m/s
  double relative_w;     // w_j - w_i, rad/s (w_disk for walls)
  double arm_i, arm_j;   // distance from each centre to the contact point, m
  double cx, cy;         // contact point, m
};

struct PairForce {
  double fn = 0, fs = 0, moment = 0;
};

// What one disk pair adds to its two disks, kept per pair when a run's
// forces are computed by several threads: the world then sums these per disk
// in pair order, the order of the serial loop, so the sums are bit-identical.
struct PairResult {
  double fx, fy;              // force on j (i gets the opposite), N
  double moment_i, moment_j;  // what each disk's moment sum gets, N m
};

// The bits of StepContext::direct.
constexpr std::uint8_t kAddToI = 1, kAddToJ = 2, kAddToBoth = 3;

// Whether pair k's contribution goes to StepContext::pair_results for the
// world to sum: always without `direct`, else unless one thread adds it to
// both of its disks.
inline bool stores_result(const std::uint8_t* direct, std::size_t k) { return !direct || direct[k] != kAddToBoth; }

// Adds one pair's contribution to the disks' sums, as the serial loop does,
// to those of its disks that `direct` names.
inline void add_pair_where(double* __restrict fx_sum, double* __restrict fy_sum, double* __restrict moment_sum,
                           std::int32_t i, std::int32_t j, const PairResult& r, std::uint8_t direct) {
  if (direct & kAddToJ) {
    fx_sum[j] += r.fx;
    fy_sum[j] += r.fy;
    moment_sum[j] += r.moment_j;
  }
  if (direct & kAddToI) {
    fx_sum[i] -= r.fx;
    fy_sum[i] -= r.fy;
    moment_sum[i] += r.moment_i;
  }
}

// Law: PairForce law(std::size_t k, const Geometry& g) for the block's pair k;
// Skip: bool skip(std::size_t k, double gap) true when the pair can be
// ignored this step at separation `gap` (> 0 apart). With step.pair_results
// set, pair k's contribution goes to pair_results[k] instead of the disks;
// with step.direct too, it goes to the disks direct[k] names and is stored
// only where that is not both.
template <bool kKeepResults, typename Law, typename Skip>
inline void for_disk_pairs_into(const PairBlock& c, Bodies& b, PairResult* __restrict results,
                                const std::uint8_t* __restrict direct, Law& law, Skip& skip) {
  // Local pointers: the loop reads and writes through them only, so the
  // compiler keeps them in registers instead of reloading them from the vectors.
  const std::int32_t* __restrict ci = c.i;
  const std::int32_t* __restrict cj = c.j;
  const double* __restrict x = b.x.data();
  const double* __restrict y = b.y.data();
  const double* __restrict r = b.radius.data();
  const double* __restrict vx = b.vx.data();
  const double* __restrict vy = b.vy.data();
  const double* __restrict w = b.w.data();
  double* __restrict fx_sum = b.fx.data();
  double* __restrict fy_sum = b.fy.data();
  double* __restrict moment_sum = b.moment.data();
  const std::size_t size = c.size;
  for (std::size_t k = 0; k < size; ++k) {
    const std::int32_t i = ci[k], j = cj[k];
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    const double distance = centre_distance_m(dx, dy);
    const double overlap = disk_overlap_m(r[i], r[j], distance);
    if (skip(k, -overlap)) {
      if constexpr (kKeepResults)
        if (stores_result(direct, k)) results[k] = PairResult{0.0, 0.0, 0.0, 0.0};
      continue;
    }
    Geometry g;
    const double inverse = 1.0 / distance;
    g.nx = dx * inverse;
    g.ny = dy * inverse;
    g.overlap = overlap;
    g.arm_i = r[i] - 0.5 * overlap;
    g.arm_j = r[j] - 0.5 * overlap;
    g.cx = x[i] + g.nx * g.arm_i;
    g.cy = y[i] + g.ny * g.arm_i;
    const double dvx = vx[j] - vx[i], dvy = vy[j] - vy[i];
    g.vn = dvx * g.nx + dvy * g.ny;
    g.vs = -dvx * g.ny + dvy * g.nx - (g.arm_i * w[i] + g.arm_j * w[j]);
    g.relative_w = w[j] - w[i];
    const PairForce f = law(k, g);
    const double fx = f.fn * g.nx - f.fs * g.ny;
    const double fy = f.fn * g.ny + f.fs * g.nx;
    const double moment_i = -g.arm_i * f.fs - f.moment;
    const double moment_j = -g.arm_j * f.fs + f.moment;
    if constexpr (kKeepResults) {
      const PairResult r{fx, fy, moment_i, moment_j};
      if (stores_result(direct, k)) results[k] = r;
      if (direct) add_pair_where(fx_sum, fy_sum, moment_sum, i, j, r, direct[k]);
    } else {
      fx_sum[j] += fx;
      fy_sum[j] += fy;
      fx_sum[i] -= fx;
      fy_sum[i] -= fy;
      moment_sum[i] += moment_i;
      moment_sum[j] += moment_j;
    }
  }
}

template <typename Law, typename Skip>
inline void for_disk_pairs(const PairBlock& c, Bodies& b, const StepContext& step, Law law, Skip skip) {
  if (step.pair_results)
    for_disk_pairs_into<true>(c, b, step.pair_results, step.direct, law, skip);
  else
    for_disk_pairs_into<false>(c, b, nullptr, nullptr, law, skip);
}

// From the wall's point nearest to (x, y) to (x, y): the offset and its length.
inline void wall_offset(const Wall& wall, double x, double y, double& dx, double& dy, double& distance) {
  const double ex = wall.x1 - wall.x0, ey = wall.y1 - wall.y0;
  const double length2 = ex * ex + ey * ey;
  double s = length2 > 0 ? ((x - wall.x0) * ex + (y - wall.y0) * ey) / length2 : 0.0;
  s = s < 0 ? 0 : (s > 1 ? 1 : s);
  const double px = wall.x0 + s * ex, py = wall.y0 + s * ey;
  dx = x - px;
  dy = y - py;
  distance = centre_distance_m(dx, dy);
}

// Disk-wall pairs: c.i is the disk, c.j the wall.
template <typename Law, typename Skip>
inline void for_wall_pairs(const PairBlock& c, Bodies& b, std::vector<Wall>& walls, Law law, Skip skip) {
  for (std::size_t k = 0; k < c.size; ++k) {
    const std::int32_t i = c.i[k];
    Wall& wall = walls[static_cast<std::size_t>(c.j[k])];
    if (!wall.active) continue;
    double dx, dy, distance;
    wall_offset(wall, b.x[i], b.y[i], dx, dy, distance);
    const double overlap = wall_overlap_m(b.radius[i], distance);
    if (skip(k, -overlap) || distance == 0.0) continue;
    Geometry g;
    g.nx = dx / distance;
    g.ny = dy / distance;
    g.overlap = overlap;
    g.arm_i = 0;
    g.arm_j = b.radius[i] - 0.5 * overlap;
    g.cx = b.x[i] - g.nx * g.arm_j;
    g.cy = b.y[i] - g.ny * g.arm_j;
    const double dvx = b.vx[i] - wall.vx, dvy = b.vy[i] - wall.vy;
    g.vn = dvx * g.nx + dvy * g.ny;
    g.vs = -dvx * g.ny + dvy * g.nx - g.arm_j * b.w[i];
    g.relative_w = b.w[i];
    const PairForce f = law(k, g);
    const double fx = f.fn * g.nx - f.fs * g.ny;
    const double fy = f.fn * g.ny + f.fs * g.nx;
    b.fx[i] += fx;
    b.fy[i] += fy;
    b.moment[i] += -g.arm_j * f.fs + f.moment;
    wall.fx -= fx;
    wall.fy -= fy;
  }
}

}  // namespace demcal::dem
