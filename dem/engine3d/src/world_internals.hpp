#pragma once
// The 3D world's working arrays (not a public header: nothing a model or a
// lab test uses).
#include <cstdint>
#include <vector>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {

// Nine values per pair: the force on i and the moments about both centres.
struct PairForceArrays {
  std::vector<double> fx, fy, fz, mix, miy, miz, mjx, mjy, mjz;
  void resize(std::size_t n) {
    for (auto* v : {&fx, &fy, &fz, &mix, &miy, &miz, &mjx, &mjy, &mjz}) v->assign(n, 0.0);
  }
  PairForces view() {
    return {fx.data(), fy.data(), fz.data(), mix.data(), miy.data(), miz.data(), mjx.data(), mjy.data(), mjz.data()};
  }
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

struct World::Internals {
  PairForceArrays sphere_pair_forces, wall_pair_forces;
  WallGeometryArrays wall_geometry;
  // Per sphere, its pairs in pair order (sphere pairs, then wall pairs):
  // entries [sum_begin[i], sum_begin[i + 1]) of sum_entry, each a pair index
  // times 4 plus how the sphere takes part (kAsI, kAsJ, kOnWall).
  std::vector<std::uint32_t> sum_begin, sum_entry;
  static constexpr std::uint32_t kAsI = 0, kAsJ = 1, kOnWall = 2;
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
};

}  // namespace demcal::dem3d
