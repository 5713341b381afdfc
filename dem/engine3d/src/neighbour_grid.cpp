// The 3D world's neighbour list: a cell grid over the spheres' bounding box
// (cells of the largest diameter plus the skin), every pair closer than the
// skin kept, in the order of the spheres' storage (which reorder_spheres sets
// from the positions and ids alone, along a Morton curve, so the order is the
// same however the spheres were given and neighbours sit close in memory).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/world.hpp"
#include "world_internals.hpp"

namespace demcal::dem3d {

namespace {

struct Grid {
  double x0 = 0, y0 = 0, z0 = 0, cell = 1;
  std::int64_t nx = 1, ny = 1, nz = 1;

  std::int64_t coordinate(double v, double v0, std::int64_t cells) const {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>((v - v0) / cell), 0, cells - 1);
  }
  std::int64_t index(std::int64_t cx, std::int64_t cy, std::int64_t cz) const { return (cz * ny + cy) * nx + cx; }
};

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

double largest_radius(const Spheres& s) {
  double r = 0;
  for (double v : s.radius) r = std::max(r, v);
  return r;
}

}  // namespace

void World::reorder_spheres() {
  const std::size_t n = spheres.size();
  const Grid g = make_grid(spheres, 2 * largest_radius(spheres) + skin_m_);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> code(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto cx = static_cast<std::uint64_t>(g.coordinate(spheres.x[i], g.x0, g.nx));
    const auto cy = static_cast<std::uint64_t>(g.coordinate(spheres.y[i], g.y0, g.ny));
    const auto cz = static_cast<std::uint64_t>(g.coordinate(spheres.z[i], g.z0, g.nz));
    code[i] = {spread_bits(cx) | spread_bits(cy) << 1 | spread_bits(cz) << 2, spheres.id[i]};
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return code[a] < code[b]; });
  spheres.permute(order);
}

void World::build_sphere_pairs(dem::ContactSet& fresh, std::vector<std::uint64_t>& keys) {
  const Spheres& s = spheres;
  const std::size_t n = s.size();
  struct Found {
    std::uint8_t model;
    std::uint32_t first, second;  // storage indices, first < second: the order
    std::uint64_t key;
    std::int32_t i, j;
  };
  std::vector<Found> found;
  if (n > 1) {
    const Grid g = make_grid(s, 2 * largest_radius(s) + skin_m_);
    const auto cells = static_cast<std::size_t>(g.nx * g.ny * g.nz);
    // The spheres by cell (a counting sort): cell c holds by_cell[start[c], start[c + 1]).
    std::vector<std::uint32_t> cell_of(n), start(cells + 1, 0), by_cell(n);
    for (std::size_t i = 0; i < n; ++i) {
      cell_of[i] = static_cast<std::uint32_t>(g.index(g.coordinate(s.x[i], g.x0, g.nx), g.coordinate(s.y[i], g.y0, g.ny),
                                                      g.coordinate(s.z[i], g.z0, g.nz)));
      ++start[cell_of[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) by_cell[next[cell_of[i]]++] = static_cast<std::uint32_t>(i);
    found.reserve(8 * n);
    for (std::size_t a = 0; a < n; ++a) {
      const std::int64_t cx = g.coordinate(s.x[a], g.x0, g.nx), cy = g.coordinate(s.y[a], g.y0, g.ny),
                         cz = g.coordinate(s.z[a], g.z0, g.nz);
      for (std::int64_t dz = -1; dz <= 1; ++dz)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dx = -1; dx <= 1; ++dx) {
            const std::int64_t x = cx + dx, y = cy + dy, z = cz + dz;
            if (x < 0 || y < 0 || z < 0 || x >= g.nx || y >= g.ny || z >= g.nz) continue;
            const auto c = static_cast<std::size_t>(g.index(x, y, z));
            for (std::uint32_t e = start[c]; e < start[c + 1]; ++e) {
              const std::size_t b = by_cell[e];
              if (b <= a) continue;  // each pair once
              const std::uint8_t model = model_for(s.group[a], s.group[b]);
              if (model == kNoModel || (s.fixed[a] && s.fixed[b])) continue;
              if (s.clump[a] >= 0 && s.clump[a] == s.clump[b]) continue;  // one rigid body
              const double ddx = s.x[b] - s.x[a], ddy = s.y[b] - s.y[a], ddz = s.z[b] - s.z[a];
              const double reach = s.radius[a] + s.radius[b] + skin_m_;
              if (ddx * ddx + ddy * ddy + ddz * ddz >= reach * reach) continue;
              // i is the sphere with the smaller id, so a pair's orientation does not depend on storage.
              const bool a_first = s.id[a] < s.id[b];
              const std::size_t i = a_first ? a : b, j = a_first ? b : a;
              found.push_back({model, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                               static_cast<std::uint64_t>(s.id[i]) << 32 | s.id[j], static_cast<std::int32_t>(i),
                               static_cast<std::int32_t>(j)});
            }
          }
    }
  }
  std::sort(found.begin(), found.end(), [](const Found& p, const Found& q) {
    return std::tie(p.model, p.first, p.second) < std::tie(q.model, q.first, q.second);
  });
  std::vector<std::size_t> per_model(models_.size(), 0);
  for (const Found& f : found) ++per_model[f.model];
  fresh.assign_blocks(per_model);
  keys.resize(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    fresh.i[k] = found[k].i;
    fresh.j[k] = found[k].j;
    keys[k] = found[k].key;
  }
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
      if (!(wall.contact(spheres.position(i), spheres.radius[i]).overlap_m > -skin_m_)) continue;
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
