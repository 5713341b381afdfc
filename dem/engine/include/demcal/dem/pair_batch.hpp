#pragma once
// Disk pairs in batches, for a model whose force law runs as one vectorised
// loop: the geometry of up to kPairBatch pairs goes into arrays, one per
// quantity (batch_geometry); the model's loop reads them and writes each
// pair's force and flags into a ForceBatch, branch-free; add_batch then walks
// the batch in pair order, logs the bonds that broke and adds the forces to
// the disks. The arithmetic is for_disk_pairs' (contact_geometry.hpp), term
// for term and in the same order, and the disks get their additions in the
// same order, so the results are the same bits: only the grouping differs.
// A vector lane rounds as a scalar does (no fused multiply-adds: the build
// forbids them), which keeps the bits whatever the vector width.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "demcal/dem/contact_geometry.hpp"
#include "demcal/dem/select.hpp"

namespace demcal::dem {

// Pairs per batch: enough for the loops to run in full vectors, few enough
// that the batch's arrays stay in the first-level cache.
constexpr std::size_t kPairBatch = 64;
static_assert(kPairBatch <= 256, "add_batch numbers a batch's pairs in bytes");

struct GeometryBatch {
  alignas(64) double nx[kPairBatch];
  alignas(64) double ny[kPairBatch];
  alignas(64) double overlap[kPairBatch];  // > 0 when touching, m
  alignas(64) double vn[kPairBatch];       // m/s
  alignas(64) double vs[kPairBatch];       // m/s
  alignas(64) double relative_w[kPairBatch];
  alignas(64) double arm_i[kPairBatch];
  alignas(64) double arm_j[kPairBatch];
};

struct ForceBatch {
  alignas(64) double fx[kPairBatch];  // force on j (i gets the opposite), N
  alignas(64) double fy[kPairBatch];
  alignas(64) double moment_i[kPairBatch];
  alignas(64) double moment_j[kPairBatch];
  alignas(64) PairFlags flags[kPairBatch];  // the pair's flags after this step
  // kBonded set in `flags` and clear here: the bond broke this step (logged by add_batch).
  alignas(64) PairFlags broke[kPairBatch];
  alignas(64) PairFlags tension[kPairBatch];  // the break's mode: 1 tension, 0 shear
};

// The geometry of the block's pairs [from, from + n), n <= kPairBatch, as
// for_disk_pairs computes it (the contact point, needed only for a break, is
// left to add_batch).
inline void batch_geometry(const PairBlock& c, const Bodies& b, std::size_t from, std::size_t n,
                           GeometryBatch& __restrict g) {
  const std::int32_t* __restrict ci = c.i + from;
  const std::int32_t* __restrict cj = c.j + from;
  const double* __restrict x = b.x.data();
  const double* __restrict y = b.y.data();
  const double* __restrict r = b.radius.data();
  const double* __restrict vx = b.vx.data();
  const double* __restrict vy = b.vy.data();
  const double* __restrict w = b.w.data();
#pragma omp simd
  for (std::size_t p = 0; p < n; ++p) {
    const std::int32_t i = ci[p], j = cj[p];
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    const double distance = centre_distance_m(dx, dy);
    const double overlap = disk_overlap_m(r[i], r[j], distance);
    const double inverse = 1.0 / distance;
    const double nx = dx * inverse, ny = dy * inverse;
    const double arm_i = r[i] - 0.5 * overlap;
    const double arm_j = r[j] - 0.5 * overlap;
    const double dvx = vx[j] - vx[i], dvy = vy[j] - vy[i];
    g.nx[p] = nx;
    g.ny[p] = ny;
    g.overlap[p] = overlap;
    g.arm_i[p] = arm_i;
    g.arm_j[p] = arm_j;
    g.vn[p] = dvx * nx + dvy * ny;
    g.vs[p] = -dvx * ny + dvy * nx - (arm_i * w[i] + arm_j * w[j]);
    g.relative_w[p] = w[j] - w[i];
  }
}

inline std::uint64_t bits_of(double v) {
  std::uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

// Adds the batch's forces to the disks in pair order (with kDirect, only to
// the disks `direct` names). With kSkipZero, only the pairs that add
// something: a sum that starts at +0 never becomes -0, so a zero term leaves
// it as it is and skipping one keeps the bits. For a model whose pairs may
// stand apart (a loose packing lists many); a batch in which every pair adds
// takes the plain loop.
template <bool kDirect, bool kSkipZero>
inline void add_to_disks(Bodies& b, const std::int32_t* __restrict ci, const std::int32_t* __restrict cj,
                         const ForceBatch& f, const std::uint8_t* __restrict direct, std::size_t n) {
  double* __restrict fx_sum = b.fx.data();
  double* __restrict fy_sum = b.fy.data();
  double* __restrict moment_sum = b.moment.data();
  auto add = [&](std::size_t p) {
    const std::int32_t i = ci[p], j = cj[p];
    if (!kDirect || direct[p] == kAddToBoth) {
      fx_sum[j] += f.fx[p];
      fy_sum[j] += f.fy[p];
      fx_sum[i] -= f.fx[p];
      fy_sum[i] -= f.fy[p];
      moment_sum[i] += f.moment_i[p];
      moment_sum[j] += f.moment_j[p];
    } else {
      add_pair_where(fx_sum, fy_sum, moment_sum, i, j, PairResult{f.fx[p], f.fy[p], f.moment_i[p], f.moment_j[p]},
                     direct[p]);
    }
  };
  if (!kSkipZero) {
    for (std::size_t p = 0; p < n; ++p) add(p);
    return;
  }
  // Whether pair p adds a term that is not +-0: in integer bits (the sign
  // shifted out), so the count vectorises.
  std::uint8_t adds[kPairBatch];
  std::size_t count = 0;
#pragma omp simd reduction(+ : count)
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint64_t any = bits_of(f.fx[p]) | bits_of(f.fy[p]) | bits_of(f.moment_i[p]) | bits_of(f.moment_j[p]);
    adds[p] = static_cast<std::uint8_t>((any << 1) != 0);
    count += adds[p];
  }
  if (count == n) {
    for (std::size_t p = 0; p < n; ++p) add(p);
    return;
  }
  std::uint8_t listed[kPairBatch];
  std::size_t m = 0;
  for (std::size_t p = 0; p < n; ++p) {
    listed[m] = static_cast<std::uint8_t>(p);
    m += adds[p];
  }
  for (std::size_t k = 0; k < m; ++k) add(listed[k]);
}

// Asks for the cache lines of column `column` of the block's pairs [next,
// next + n) ahead of their use. The law reads and writes a batch's state only
// after the batch's geometry, so without this the state of a large specimen
// arrives one miss at a time once the law starts (the parallel bond, one
// thread: 47k disks 1.13x the time without it, 19k 1.05x). Only for a
// block whose state exceeds kPrefetchAboveBytes: below it the caches and
// their own prefetchers keep up and the requests cost time (9.5k disks, 2.8
// MB of state: 1.05x with them).
constexpr std::size_t kPrefetchAboveBytes = std::size_t{4} << 20;
inline void prefetch_state_column(const PairBlock& c, std::size_t column, std::size_t next, std::size_t n) {
  const char* const first = reinterpret_cast<const char*>(&c.column(column, next));
  const char* const last = first + n * sizeof(double) - 1;
  for (const char* line = first; line < last; line += 64) __builtin_prefetch(line, 1, 3);
  __builtin_prefetch(last, 1, 3);
}

// Pair by pair in order: the new flags, a break's log entry (its contact
// point as for_disk_pairs computes it), and the forces, added to the disks or,
// with step.pair_results, stored per pair for the world's threaded sum (and
// added to the disks step.direct names).
template <bool kSkipZero>
inline void add_batch(const PairBlock& c, Bodies& b, std::size_t from, std::size_t n, const GeometryBatch& g,
                      const ForceBatch& f, const StepContext& step) {
  PairFlags* __restrict flags = c.flags + from;
  const std::int32_t* __restrict ci = c.i + from;
  const std::int32_t* __restrict cj = c.j + from;
  // The next batch's state, fetched while this batch's forces go to the disks.
  const std::size_t columns = c.column.columns;
  const bool large = c.size * columns * sizeof(double) > kPrefetchAboveBytes;
  const std::size_t next = from + n, ahead = large ? std::min(n, c.size - next) : 0;
  if (ahead)
    for (std::size_t column = 0; column < columns; ++column) prefetch_state_column(c, column, next, ahead);
  std::memcpy(flags, f.flags, n * sizeof(PairFlags));
  // Breaks are rare: one vectorised look for any, then the log in pair order.
  PairFlags any_broke = 0;
#pragma omp simd reduction(| : any_broke)
  for (std::size_t p = 0; p < n; ++p) any_broke |= f.broke[p];
  if (any_broke && step.breaks)
    for (std::size_t p = 0; p < n; ++p)
      if (f.broke[p]) {
        const std::size_t i = static_cast<std::size_t>(ci[p]), j = static_cast<std::size_t>(cj[p]);
        step.breaks->push_back({step.time_s, b.x[i] + g.nx[p] * g.arm_i[p], b.y[i] + g.ny[p] * g.arm_i[p],
                                f.tension[p] ? BreakMode::Tension : BreakMode::Shear, b.group[i], b.group[j]});
      }
  PairResult* __restrict results = step.pair_results ? step.pair_results + from : nullptr;
  const std::uint8_t* __restrict direct = step.direct ? step.direct + from : nullptr;
  if (results) {
    // Stored for every pair the world sums from `results` (all of them, or
    // those with a disk that `direct` leaves out).
    for (std::size_t p = 0; p < n; ++p)
      if (stores_result(direct, p)) results[p] = PairResult{f.fx[p], f.fy[p], f.moment_i[p], f.moment_j[p]};
    if (!direct) return;
  }
  if (direct)
    add_to_disks<true, kSkipZero>(b, ci, cj, f, direct, n);
  else
    add_to_disks<false, kSkipZero>(b, ci, cj, f, nullptr, n);
}

// Whether every pair of [from, from + n) stands apart on the distance alone:
// its squared distance, computed as batch_geometry computes it, exceeds
// (r_i + r_j)^2 by far more than rounding, so sqrt rounds to at least
// r_i + r_j and the overlap is <= 0. Looks at 8 pairs at a time and stops at
// the first group with a pair that may touch, so a packed batch costs little.
inline bool batch_stands_apart(const PairBlock& c, const Bodies& b, std::size_t from, std::size_t n) {
  const std::int32_t* __restrict ci = c.i + from;
  const std::int32_t* __restrict cj = c.j + from;
  const double* __restrict x = b.x.data();
  const double* __restrict y = b.y.data();
  const double* __restrict r = b.radius.data();
  // (1 + 2^-30): the product and its rounding stay above the exact square.
  constexpr double kMargin = 1.0 + 1.0 / 1073741824.0;
  constexpr std::size_t kGroup = 8;
  for (std::size_t start = 0; start < n; start += kGroup) {
    const std::size_t end = n - start < kGroup ? n : start + kGroup;
    unsigned near = 0;
#pragma omp simd reduction(| : near)
    for (std::size_t p = start; p < end; ++p) {
      const std::int32_t i = ci[p], j = cj[p];
      const double dx = x[j] - x[i], dy = y[j] - y[i];
      const double reach = r[i] + r[j];
      near |= static_cast<unsigned>(!(dx * dx + dy * dy > reach * reach * kMargin));
    }
    if (near) return false;
  }
  return true;
}

// What add_batch stores for a batch whose forces are all +0: nothing goes to
// the disks, but the stored results the world sums must not keep an earlier
// step's forces.
inline void store_zero_results(const StepContext& step, std::size_t from, std::size_t n) {
  if (!step.pair_results) return;
  PairResult* __restrict results = step.pair_results + from;
  const std::uint8_t* __restrict direct = step.direct ? step.direct + from : nullptr;
  for (std::size_t p = 0; p < n; ++p)
    if (stores_result(direct, p)) results[p] = PairResult{0.0, 0.0, 0.0, 0.0};
}

// The default for models without a shortcut for batches standing apart.
struct NoApartShortcut {
  bool operator()(std::size_t, std::size_t) const { return false; }
};

// A model's disk_forces over its block in batches: law(from, n, g, f) fills
// `f` for pairs [from, from + n) from their geometry `g` (and updates their
// state); the forces then go to the disks or to step.pair_results (with
// kSkipZero, zero contributions are not added: see add_to_disks).
// apart(from, n) may take a whole batch instead, when it finds that none of
// its pairs touches and gives them what the law would (its state and flags,
// and zero forces: see store_zero_results); it returns whether it did.
template <bool kSkipZero = false, typename Law, typename Apart = NoApartShortcut>
inline void for_pair_batches(const PairBlock& c, Bodies& b, const StepContext& step, Law law, Apart apart = {}) {
  GeometryBatch g;
  ForceBatch f;
  for (std::size_t from = 0; from < c.size; from += kPairBatch) {
    const std::size_t n = c.size - from < kPairBatch ? c.size - from : kPairBatch;
    if (apart(from, n)) continue;
    batch_geometry(c, b, from, n, g);
    law(from, n, g, f);
    add_batch<kSkipZero>(c, b, from, n, g, f, step);
  }
}

}  // namespace demcal::dem
