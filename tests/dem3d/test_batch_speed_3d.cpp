// A guard on the batched laws' speed, as a ratio inside one process (no
// absolute time, which the machine sets): a compressed sphere lattice in a
// box, every pair touching, stepped with the linear law and with the parallel
// bond on every pair. The bond's single batch loop costs about 0.7 of the
// linear law's step here (2026-12-07, the 2-core Intel Xeon: 0.018 s against
// 0.025 s for 60 steps); a batch loop that compiles but runs its scalar path
// (as a helper called through a by-reference lambda once did: 2.3x slower) or
// spills from a too-wide vector pushes the ratio past 1.5.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include <nlohmann/json.hpp>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/walls.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650;
constexpr int kSide = 14;                       // 2,744 spheres, about 7,700 pairs
constexpr double kSpacing = 1.998 * kRadius;    // every neighbour pair overlaps 2 um

std::unique_ptr<World> lattice(const std::string& model, const nlohmann::json& parameters) {
  WorldSettings settings;
  settings.threads = 1;
  settings.damping = 0;
  auto world = std::make_unique<World>(settings);
  const auto m = world->add_model(ContactModelRegistry::instance().create(model, parameters, "test"));
  world->assign(0, 0, m);
  const auto wall_model = world->add_model(ContactModelRegistry::instance().create(
      "linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}}, "test"));
  world->assign(0, 1, wall_model);
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      for (int k = 0; k < kSide; ++k)
        world->spheres.add_sphere({i * kSpacing, j * kSpacing, k * kSpacing}, kRadius, kDensity, 0);
  // Six planes pressing the outer spheres by the same overlap: the lattice
  // starts (and stays) in equilibrium, every pair touching.
  // A wall's linear spring is twice a pair's (pi r^2 E / L with L = R, not 2R), so half the overlap balances.
  const double wall_overlap = 0.5 * (2 * kRadius - kSpacing);
  const double near = -(kRadius - wall_overlap), far = (kSide - 1) * kSpacing + (kRadius - wall_overlap);
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 n{0, 0, 0}, p{0, 0, 0};
    auto set = [&](Vec3& v, double value) { (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = value; };
    set(n, 1.0), set(p, near);
    world->walls.push_back(make_plane(p, n));
    set(n, -1.0), set(p, far);
    world->walls.push_back(make_plane(p, n));
  }
  world->refresh();
  if (model == "parallel_bond") world->install_bonds(0.01 * kRadius, 1);
  return world;
}

// The least time of `samples` runs of `steps` steps (the least is the run the
// machine disturbed least).
double least_seconds(World& world, int steps, int samples) {
  double least = 1e300;
  for (int s = 0; s < samples; ++s) {
    const auto start = std::chrono::steady_clock::now();
    world.run(static_cast<std::uint64_t>(steps));
    least = std::min(least, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return least;
}

}  // namespace

TEST(BatchSpeed3D, TheParallelBondCostsLessThanOneAndAHalfLinearLaws) {
  const nlohmann::json linear = {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}};
  nlohmann::json bonded = linear;
  bonded.update({{"bond_modulus_pa", 2e9}, {"bond_kn_ks", 2.0}, {"radius_multiplier", 1.0},
                 {"tensile_strength_pa", 1e12}, {"shear_strength_pa", 1e12}});
  auto a = lattice("linear", linear);
  auto b = lattice("parallel_bond", bonded);
  ASSERT_GT(b->bonded_pairs(), 7000u);
  a->step(), b->step();  // the lists built, outside the timing
  const int steps = 60;
  double linear_s = 1e300, bonded_s = 1e300;
  for (int round = 0; round < 4; ++round) {  // in turn, so a slow minute of the machine slows both
    linear_s = std::min(linear_s, least_seconds(*a, steps, 2));
    bonded_s = std::min(bonded_s, least_seconds(*b, steps, 2));
  }
  EXPECT_EQ(a->touching_pairs(), b->touching_pairs());
  EXPECT_GT(a->touching_pairs(), 7000u);
  EXPECT_LT(bonded_s / linear_s, 1.5) << "linear " << linear_s << " s, parallel bond " << bonded_s << " s for "
                                      << steps << " steps";
}
