#pragma once
// The 3D world's working arrays (not a public header: nothing a model or a
// lab test uses).
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {

enum SumField : std::size_t { kSumFx, kSumFy, kSumFz, kSumMx, kSumMy, kSumMz };
constexpr std::size_t kSumStride = 8;

// Nine values per pair: the force on i, and the moments about both centres (i's at 2k, j's at 2k + 1).
struct PairForceArrays {
  std::vector<double> fx, fy, fz, mx, my, mz;
  void resize(std::size_t n) {
    for (auto* v : {&fx, &fy, &fz}) v->assign(n, 0.0);
    for (auto* v : {&mx, &my, &mz}) v->assign(2 * n, 0.0);
  }
  PairForces view() { return {fx.data(), fy.data(), fz.data(), mx.data(), my.data(), mz.data()}; }
};

// The contact geometry of every wall pair at this step.
struct WallGeometryArrays {
  std::vector<double> nx, ny, nz, overlap, vx, vy, vz;
  std::vector<WallFeature> feature;
  void resize(std::size_t n) {
    for (auto* v : {&nx, &ny, &nz, &overlap, &vx, &vy, &vz}) v->assign(n, 0.0);
    feature.assign(n, WallFeature::face);
  }
  WallGeometry view() const {
    return {nx.data(), ny.data(), nz.data(), overlap.data(), vx.data(), vy.data(), vz.data()};
  }
};

// The cell grid of a rebuild over the spheres' bounding box (neighbour_grid.cpp).
struct CellGrid {
  double x0 = 0, y0 = 0, z0 = 0, cell = 1;
  std::int64_t nx = 1, ny = 1, nz = 1;

  std::int64_t coordinate(double v, double v0, std::int64_t cells) const {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>((v - v0) / cell), 0, cells - 1);
  }
  std::int64_t index(std::int64_t cx, std::int64_t cy, std::int64_t cz) const { return (cz * ny + cy) * nx + cx; }
};

// The neighbour search's working arrays, kept from one rebuild to the next:
// a released specimen rebuilds every few steps, and fresh arrays of this size
// cost page faults and zeroing each time (neighbour_grid.cpp says what each holds).
struct NeighbourScratch {
  std::vector<std::uint32_t> start, by_cell, cell_of, next, row_start, second;
  std::vector<double> cx, cy, cz, cr;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> close;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found;
};

struct World::Internals {
  // The grid reorder_spheres made at this rebuild: the search reuses it (a
  // reorder moves no sphere, so the bounding box is the same).
  CellGrid grid;
  NeighbourScratch search;
  // The lists of the build before last, whose storage the next build fills.
  dem::ContactSet spare_pairs, spare_wall_pairs;
  std::vector<std::uint64_t> spare_keys, spare_wall_keys;
  PairForceArrays sphere_pair_forces, wall_pair_forces;
  WallGeometryArrays wall_geometry;
  // Per sphere, its sphere pairs in pair order: entries [sum_begin[i],
  // sum_begin[i + 1]) of sum_entry, each 2 k for pair k's i, 2 k + 1 for its j
  // (the moment's index; the force's sign); then its wall pairs likewise in
  // wall_begin and wall_entry (entries k).
  std::vector<std::uint32_t> sum_begin, sum_entry, wall_begin, wall_entry;
  // On one thread the sphere pairs add straight into these per-sphere sums
  // (PairForces direct), in pair order: the same sums as the stored path.
  // Each sphere's sums side by side: fx, fy, fz, mx, my, mz at kSum* of its
  // kSumStride values (one cache line).
  // The integration zeroes each chunk of them once it has read it, while it is
  // in cache (sums_zero then holds), so the next step need not clear them.
  std::vector<double> sums;
  bool sums_zero = false;
  bool direct = false;
  std::vector<double> x_built, y_built, z_built;
  // The walls as they were at the last build, and the spheres' extent then
  // (a turning plane or cylinder moves by its angle times that extent at most).
  std::vector<Wall> walls_built;
  double extent_m = 0;
  std::vector<double> inverse_mass, inverse_inertia;
  double max_move2 = 0;
  // Clumps: each clump's members as sphere indices now (refreshed at every
  // rebuild, which reorders the spheres), the members' summed forces and
  // moments of the step (by sphere index), and each clump's net force.
  std::vector<std::vector<std::size_t>> member_index;
  std::vector<double> member_fx, member_fy, member_fz, member_mx, member_my, member_mz;
  std::vector<Vec3> clump_force;
  // Each sphere's record for the vectorised laws (sphere_records.hpp), refreshed each step.
  std::vector<double> records;
  // Type A rolling resistance: each sphere's couple limit this step (empty
  // when no model adds one).
  std::vector<double> rolling_limit;
};

}  // namespace demcal::dem3d
