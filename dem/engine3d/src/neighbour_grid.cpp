// The 3D world's neighbour list: a cell grid over the spheres' bounding box
// (cells of the largest diameter plus the skin), every pair closer than the
// skin kept, in the order of the spheres' storage (which reorder_spheres sets
// from the positions and ids alone, along a Morton curve, so the order is the
// same however the spheres were given and neighbours sit close in memory).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/world.hpp"
#include "world_internals.hpp"

namespace demcal::dem3d {

namespace {

using Grid = CellGrid;

// A grid over the spheres with cells at least `cell_m` wide, and at most
// about 4 cells per sphere (a sparse packing would otherwise ask for more
// cells than memory).
Grid make_grid(const Spheres& s, double cell_m) {
  Grid g;
  if (s.size() == 0) return g;
  double x1 = -INFINITY, y1 = -INFINITY, z1 = -INFINITY;
  g.x0 = g.y0 = g.z0 = INFINITY;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.z[i]))
      throw Error("sphere " + std::to_string(s.id[i]) + " has a position that is not finite (an unstable run)");
    g.x0 = std::min(g.x0, s.x[i]), x1 = std::max(x1, s.x[i]);
    g.y0 = std::min(g.y0, s.y[i]), y1 = std::max(y1, s.y[i]);
    g.z0 = std::min(g.z0, s.z[i]), z1 = std::max(z1, s.z[i]);
  }
  g.cell = cell_m;
  const double most_cells = 4.0 * static_cast<double>(s.size()) + 64;
  const auto cells_over = [&](double xa, double xb, double ya, double yb, double za, double zb) {
    return (std::floor((xb - xa) / g.cell) + 1) * (std::floor((yb - ya) / g.cell) + 1) *
           (std::floor((zb - za) / g.cell) + 1);
  };
  if (cells_over(g.x0, x1, g.y0, y1, g.z0, z1) > most_cells && s.size() >= 1000) {
    // A few spheres far from the rest (escaped from a vessel, flung out of a
    // drum) would make every cell huge and the search quadratic. The grid
    // then spans the middle 99.8 % of the spheres on each axis, a cell wider,
    // and the rest fall into its edge cells: coordinate() clamps, which never
    // puts two spheres closer than a cell more than one cell apart, so no pair
    // is lost.
    const auto middle = [&](const std::vector<double>& v, double& low, double& high) {
      std::vector<double> sorted = v;
      const std::size_t a = sorted.size() / 1000, b = sorted.size() - 1 - sorted.size() / 1000;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(a), sorted.end());
      const double q_low = sorted[a];
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(b), sorted.end());
      const double q_high = sorted[b];
      low = std::max(low, q_low - g.cell);
      high = std::min(high, q_high + g.cell);
    };
    middle(s.x, g.x0, x1);
    middle(s.y, g.y0, y1);
    middle(s.z, g.z0, z1);
  }
  for (;;) {
    g.nx = static_cast<std::int64_t>((x1 - g.x0) / g.cell) + 1;
    g.ny = static_cast<std::int64_t>((y1 - g.y0) / g.cell) + 1;
    g.nz = static_cast<std::int64_t>((z1 - g.z0) / g.cell) + 1;
    if (static_cast<double>(g.nx) * static_cast<double>(g.ny) * static_cast<double>(g.nz) <= most_cells) return g;
    g.cell *= 1.5;
  }
}

// The 21 low bits of v spread to every third bit (Morton order).
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// Whether two spheres at centre offset (dx, dy, dz) are within the skin of
// each other, the same bits in either order (the neighbour search and the
// kept bonds must agree on every pair).
inline bool within_skin(double dx, double dy, double dz, double radius_a, double radius_b, double skin_m) {
  const double reach = (radius_a + radius_b) + skin_m;
  return dx * dx + dy * dy + dz * dz < reach * reach;
}

// The search's test of a run of cell-ordered entries against one entry, a
// group of kLanes entries at a time (GCC/Clang vector extensions): the same
// operations as within_skin, lane by lane, so the same pairs.
constexpr std::size_t kLanes = 4;
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

inline Lanes load_lanes(const double* from) {
  Lanes v;
  std::memcpy(&v, from, sizeof v);
  return v;
}

struct RunScanner {
  const double *cx, *cy, *cz, *cr;  // entries in cell order, padded by kLanes unreachable ones
  double skin_m;

  // Calls keep(q) for each entry q in [from, to) within the skin of entry e, in order.
  template <typename Keep>
  void scan(std::size_t e, std::size_t from, std::size_t to, Keep&& keep) const {
    const Lanes xa = Lanes{} + cx[e], ya = Lanes{} + cy[e], za = Lanes{} + cz[e], ra = Lanes{} + cr[e];
    const Lanes skin = Lanes{} + skin_m;
    for (std::size_t q = from; q < to; q += kLanes) {
      const Lanes dx = load_lanes(cx + q) - xa, dy = load_lanes(cy + q) - ya, dz = load_lanes(cz + q) - za;
      const Lanes reach = (ra + load_lanes(cr + q)) + skin;
      const auto hit = dx * dx + dy * dy + dz * dz < reach * reach;
      bool any = false;
      for (std::size_t k = 0; k < kLanes; ++k) any |= hit[k] != 0;
      if (!any) continue;
      for (std::size_t k = 0; k < kLanes && q + k < to; ++k)
        if (hit[k]) keep(q + k);
    }
  }
};

double largest_radius(const Spheres& s) {
  double r = 0;
  for (double v : s.radius) r = std::max(r, v);
  return r;
}

}  // namespace

void World::reorder_spheres() {
  const std::size_t n = spheres.size();
  internals_->grid = make_grid(spheres, 2 * largest_radius(spheres) + skin_m_);
  const Grid& g = internals_->grid;
  // Sorted by (code, id), a total order: any sort gives the same order. Most
  // rebuilds find the spheres still in it (they moved less than a skin since
  // the last), and then nothing moves.
  struct Key {
    std::uint64_t code;
    std::uint32_t id, index;
    bool operator<(const Key& o) const { return code < o.code || (code == o.code && id < o.id); }
  };
  std::vector<Key> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto cx = static_cast<std::uint64_t>(g.coordinate(spheres.x[i], g.x0, g.nx));
    const auto cy = static_cast<std::uint64_t>(g.coordinate(spheres.y[i], g.y0, g.ny));
    const auto cz = static_cast<std::uint64_t>(g.coordinate(spheres.z[i], g.z0, g.nz));
    keys[i] = {spread_bits(cx) | spread_bits(cy) << 1 | spread_bits(cz) << 2, spheres.id[i], static_cast<std::uint32_t>(i)};
  }
  if (std::is_sorted(keys.begin(), keys.end())) return;
  // A least-significant-digit radix sort (stable), id digits first, then the
  // code's: the order std::sort would give, in a few passes.
  std::vector<Key> spare(n);
  std::uint64_t highest_code = 0, highest_id = 0;
  for (const Key& k : keys) {
    highest_code = std::max(highest_code, k.code);
    highest_id = std::max<std::uint64_t>(highest_id, k.id);
  }
  const auto by_digits = [&](auto digit_of, std::uint64_t highest) {
    constexpr unsigned kBits = 11;
    constexpr std::size_t kBuckets = std::size_t{1} << kBits;
    for (unsigned shift = 0; shift < 64 && (highest >> shift) != 0; shift += kBits) {
      std::vector<std::uint32_t> count(kBuckets + 1, 0);
      for (const Key& k : keys) ++count[((digit_of(k) >> shift) & (kBuckets - 1)) + 1];
      for (std::size_t b = 0; b < kBuckets; ++b) count[b + 1] += count[b];
      for (const Key& k : keys) spare[count[(digit_of(k) >> shift) & (kBuckets - 1)]++] = k;
      keys.swap(spare);
    }
  };
  by_digits([](const Key& k) { return static_cast<std::uint64_t>(k.id); }, highest_id);
  by_digits([](const Key& k) { return k.code; }, highest_code);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].index;
  spheres.permute(order);
}

void World::build_sphere_pairs(dem::ContactSet& fresh, std::vector<std::uint64_t>& keys) {
  const Spheres& s = spheres;
  const std::size_t n = s.size();
  NeighbourScratch& scratch = internals_->search;  // every array below is refilled before it is read
  // Each model's pairs as (first, second) storage indices, first < second,
  // in (first, second) order.
  auto& found = scratch.found;
  found.resize(models_.size());
  for (auto& list : found) list.clear();
  if (n > 1) {
    const Grid& g = internals_->grid;  // reorder_spheres made it at this rebuild
    const auto cells = static_cast<std::size_t>(g.nx * g.ny * g.nz);
    // The spheres by cell (a counting sort): cell c holds entries [start[c],
    // start[c + 1]), and a row of cells along x is one run of entries. Their
    // centres and reaches are copied in that order, so the search below reads
    // runs of memory.
    auto &start = scratch.start, &by_cell = scratch.by_cell, &cell_of = scratch.cell_of;
    start.assign(cells + 1, 0);
    by_cell.resize(n);
    cell_of.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      cell_of[i] = static_cast<std::uint32_t>(g.index(g.coordinate(s.x[i], g.x0, g.nx),
                                                      g.coordinate(s.y[i], g.y0, g.ny),
                                                      g.coordinate(s.z[i], g.z0, g.nz)));
      ++start[cell_of[i] + std::size_t{1}];
    }
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    {
      auto& next = scratch.next;
      next.assign(start.begin(), start.end() - 1);
      for (std::size_t i = 0; i < n; ++i) by_cell[next[cell_of[i]]++] = static_cast<std::uint32_t>(i);
    }
    // Padded by a lane group of entries that no sphere reaches (infinitely far,
    // radius 0), so a scan may read a whole group past its run.
    auto &cx = scratch.cx, &cy = scratch.cy, &cz = scratch.cz, &cr = scratch.cr;
    cx.assign(n + kLanes, INFINITY), cy.assign(n + kLanes, INFINITY), cz.assign(n + kLanes, INFINITY);
    cr.assign(n + kLanes, 0.0);
    for (std::size_t e = 0; e < n; ++e) {
      const std::uint32_t i = by_cell[e];
      cx[e] = s.x[i], cy[e] = s.y[i], cz[e] = s.z[i], cr[e] = s.radius[i];
    }
    // Each pair once, from the entry that comes first in cell order: the rest
    // of its own cell and the next one along x, the row above in y, and the
    // three rows above in z (13 of the 26 neighbour cells).
    auto& close = scratch.close;  // (first, second) storage indices
    close.clear();
    close.reserve(8 * n);
    const RunScanner scanner{cx.data(), cy.data(), cz.data(), cr.data(), skin_m_};
    for (std::size_t e = 0; e < n; ++e) {
      const std::int64_t c = cell_of[by_cell[e]];
      const std::int64_t x = c % g.nx, y = (c / g.nx) % g.ny, z = c / (g.nx * g.ny);
      const std::int64_t x0 = std::max<std::int64_t>(x - 1, 0), x1 = std::min(x + 1, g.nx - 1);
      const std::uint32_t a = by_cell[e];
      const auto keep = [&](std::size_t q) {
        const std::uint32_t b = by_cell[q];
        close.emplace_back(std::min(a, b), std::max(a, b));
      };
      const auto row = [&](std::int64_t ry, std::int64_t rz) {
        scanner.scan(e, start[static_cast<std::size_t>(g.index(x0, ry, rz))],
                     start[static_cast<std::size_t>(g.index(x1, ry, rz)) + 1], keep);
      };
      scanner.scan(e, e + 1, start[static_cast<std::size_t>(g.index(x1, y, z)) + 1], keep);
      if (y + 1 < g.ny) row(y + 1, z);
      if (z + 1 < g.nz)
        for (std::int64_t ry = std::max<std::int64_t>(y - 1, 0); ry <= std::min(y + 1, g.ny - 1); ++ry) row(ry, z + 1);
    }
    // In (first, second) order: by first (a counting sort), then each first's short row by second.
    auto& row_start = scratch.row_start;
    row_start.assign(n + 1, 0);
    for (const auto& [a, b] : close) ++row_start[a + std::size_t{1}];
    for (std::size_t i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
    auto& second = scratch.second;
    second.resize(close.size());
    {
      auto& next = scratch.next;
      next.assign(row_start.begin(), row_start.end() - 1);
      for (const auto& [a, b] : close) second[next[a]++] = b;
    }
    for (auto& list : found) list.reserve(close.size());
    for (std::size_t a = 0; a < n; ++a) {
      const auto first = second.begin() + row_start[a], last = second.begin() + row_start[a + 1];
      std::sort(first, last);
      for (auto it = first; it != last; ++it) {
        const std::uint32_t b = *it;
        const std::uint8_t model = model_for(s.group[a], s.group[b]);
        if (model == kNoModel || (s.fixed[a] && s.fixed[b])) continue;
        if (s.clump[a] >= 0 && s.clump[a] == s.clump[b]) continue;  // one rigid body
        found[model].emplace_back(static_cast<std::uint32_t>(a), b);
      }
    }
  }
  keep_bonded_pairs(found);
  std::vector<std::size_t> per_model(models_.size(), 0);
  for (std::size_t m = 0; m < found.size(); ++m) per_model[m] = found[m].size();
  fresh.assign_blocks(per_model);
  keys.resize(fresh.size());
  std::size_t k = 0;
  for (const auto& list : found)
    for (const auto& [a, b] : list) {
      // i is the sphere with the smaller id, so a pair's orientation does not depend on storage.
      const bool a_first = s.id[a] < s.id[b];
      const std::uint32_t i = a_first ? a : b, j = a_first ? b : a;
      fresh.i[k] = static_cast<std::int32_t>(i);
      fresh.j[k] = static_cast<std::int32_t>(j);
      keys[k++] = static_cast<std::uint64_t>(s.id[i]) << 32 | s.id[j];
    }
}

// A bond holds its pair in the list however far apart its spheres have
// moved: the bonded pairs of the old list the search did not find (beyond
// the skin), by their ids, at their (first, second) places.
void World::keep_bonded_pairs(std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>>& found) const {
  const Spheres& s = spheres;
  std::vector<std::uint32_t> index_of_id;
  bool any = false;
  for (std::size_t k = 0; k < pairs_.size() && !any; ++k) any = (pairs_.flags[k] & dem::kBonded) != 0;
  if (!any) return;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.id[i] >= index_of_id.size()) index_of_id.resize(s.id[i] + std::size_t{1}, UINT32_MAX);
    index_of_id[s.id[i]] = static_cast<std::uint32_t>(i);
  }
  std::vector<std::uint8_t> grown(found.size(), 0);
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    if (!(pairs_.flags[k] & dem::kBonded)) continue;
    const std::uint64_t id_i = pair_keys_[k] >> 32, id_j = pair_keys_[k] & 0xffffffffu;
    if (id_i >= index_of_id.size() || id_j >= index_of_id.size()) continue;
    const std::uint32_t p = index_of_id[id_i], q = index_of_id[id_j];
    if (p == UINT32_MAX || q == UINT32_MAX) continue;  // a sphere was removed
    const std::uint32_t a = std::min(p, q), b = std::max(p, q);
    if ((s.fixed[a] && s.fixed[b]) || (s.clump[a] >= 0 && s.clump[a] == s.clump[b])) continue;
    // The search's own test, so a pair is found once: by it or here.
    if (within_skin(s.x[b] - s.x[a], s.y[b] - s.y[a], s.z[b] - s.z[a], s.radius[a], s.radius[b], skin_m_)) continue;
    const std::uint8_t model = pairs_.model[k];
    found[model].emplace_back(a, b);
    grown[model] = 1;
  }
  for (std::size_t m = 0; m < found.size(); ++m)
    if (grown[m]) std::sort(found[m].begin(), found[m].end());
}

void World::build_wall_pairs(dem::ContactSet& fresh, std::vector<std::uint64_t>& keys) {
  struct Found {
    std::uint8_t model;
    std::uint64_t key;
    std::int32_t i, wall;
  };
  std::vector<Found> found;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& wall = walls[w];
    if (!wall.active) continue;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      const std::uint8_t model = model_for(spheres.group[i], wall.group);
      if (model == kNoModel || spheres.fixed[i]) continue;
      // A bounded cylinder lists the spheres within a skin beyond its ends too
      // (one drifting in along the axis must find its pair there).
      Wall probe = wall;
      const bool cylinder = wall.shape == WallShape::cylinder_inside || wall.shape == WallShape::cylinder_outside;
      if (cylinder && wall.length_m > 0) {
        const double along = dot(spheres.position(i) - wall.point_m, wall.axis), margin = spheres.radius[i] + skin_m_;
        if (along < -margin || along > wall.length_m + margin) continue;
        probe.length_m = 0;
      }
      if (!(probe.contact(spheres.position(i), spheres.radius[i]).overlap_m > -skin_m_)) continue;
      found.push_back({model, static_cast<std::uint64_t>(spheres.id[i]) << 32 | w, static_cast<std::int32_t>(i),
                       static_cast<std::int32_t>(w)});
    }
  }
  std::sort(found.begin(), found.end(), [](const Found& p, const Found& q) {
    return std::tie(p.model, p.i, p.wall) < std::tie(q.model, q.i, q.wall);
  });
  std::vector<std::size_t> per_model(models_.size(), 0);
  for (const Found& f : found) ++per_model[f.model];
  fresh.assign_blocks(per_model);
  keys.resize(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    fresh.i[k] = found[k].i;
    fresh.j[k] = found[k].wall;
    keys[k] = found[k].key;
  }
}

}  // namespace demcal::dem3d
