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

struct World::Internals {
  PairForceArrays sphere_pair_forces, plane_pair_forces;
  // Per sphere, its pairs in pair order (sphere pairs, then plane pairs):
  // entries [sum_begin[i], sum_begin[i + 1]) of sum_entry, each a pair index
  // times 4 plus how the sphere takes part (kAsI, kAsJ, kOnPlane).
  std::vector<std::uint32_t> sum_begin, sum_entry;
  static constexpr std::uint32_t kAsI = 0, kAsJ = 1, kOnPlane = 2;
  std::vector<double> x_built, y_built, z_built;
  std::vector<Vec3> planes_built;
  std::vector<double> inverse_mass, inverse_inertia;
  double max_move2 = 0;
};

}  // namespace demcal::dem3d
