// The vectorised linear law (linear_batch.hpp) against the scalar loop it
// replaces (for_sphere_pairs with LinearBase::linear_touch), bit for bit:
// pairs touching and apart, sticking and sliding, a reference overlap, a
// stored shear force, spins and velocities in every direction; a block longer
// than one batch and not a multiple of it; forces stored per pair and added
// straight to the spheres; whole batches of pairs apart.
#include <gtest/gtest.h>

#include <cstring>

#include <nlohmann/json.hpp>

#include "demcal/core/rng.hpp"
#include "demcal/dem3d/linear_base.hpp"
#include "demcal/dem3d/linear_batch.hpp"

using namespace demcal::dem3d;
namespace dem = demcal::dem;

namespace {

const nlohmann::json kParameters = {{"kn_n_m", 1e5}, {"ks_n_m", 4e4}, {"friction", 0.3}};

// The law as it was before it ran in batches.
class ScalarLinear : public LinearBase {
 public:
  using LinearBase::LinearBase;
  std::string name() const override { return "scalar linear"; }
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    for_sphere_pairs(
        c, s, [&](std::size_t k, const PairContact& p) { linear_touch(c, k, out, p, step.dt_s); },
        [&](std::size_t k) { linear_leave(c, k, out); });
  }
};

class BatchedLinear : public LinearBase {
 public:
  using LinearBase::LinearBase;
  std::string name() const override { return "batched linear"; }
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    linear_batch::linear_sphere_forces(c, s, out, step);
  }
};

// Spheres scattered in a small box, every pair within 1.2 times their radii
// summed listed (about half of them touch).
struct Scene {
  Spheres s;
  dem::ContactSet set;
};

Scene make_scene(std::uint64_t seed, std::size_t columns) {
  demcal::Rng rng(seed);
  Scene scene;
  const double radius = 1e-3;
  for (int k = 0; k < 90; ++k) {
    scene.s.add_sphere({rng.uniform(0, 9e-3), rng.uniform(0, 9e-3), rng.uniform(0, 9e-3)},
                       radius * rng.uniform(0.8, 1.2), 2650, 0);
    const std::size_t i = scene.s.size() - 1;
    scene.s.set_velocity(i, {rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)});
    scene.s.set_spin(i, {rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50)});
  }
  // Then 20 spheres in a row far away, every pair of them listed and apart:
  // more than two whole batches in which no pair touches.
  const std::size_t close = scene.s.size();
  for (int k = 0; k < 20; ++k) scene.s.add_sphere({1.0 + 0.01 * k, 0, 0}, radius, 2650, 0);
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t i = 0; i < close; ++i)
    for (std::size_t j = i + 1; j < close; ++j) {
      const Vec3 d = scene.s.position(j) - scene.s.position(i);
      const double reach = 1.2 * (scene.s.radius[i] + scene.s.radius[j]);
      if (dot(d, d) < reach * reach) pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  for (std::size_t i = close; i < scene.s.size(); ++i)
    for (std::size_t j = i + 1; j < scene.s.size(); ++j) pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
  scene.set.set_layout({columns});
  scene.set.assign_blocks({pairs.size()});
  for (std::size_t k = 0; k < pairs.size(); ++k) scene.set.i[k] = pairs[k].first, scene.set.j[k] = pairs[k].second;
  return scene;
}

std::uint64_t bits(double v) {
  std::uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

struct Outcome {
  std::vector<double> state, forces, sums;
  std::vector<dem::PairFlags> flags;
};

// Ten steps of `model` over the scene (the spheres do not move: the stored
// shear forces grow, turn and slide), forces stored or added direct.
Outcome run(const LinearBase& model, std::uint64_t seed, bool direct) {
  Scene scene = make_scene(seed, model.state_columns().size());
  dem::PairBlock block = scene.set.block(0);
  demcal::Rng rng(seed + 1);
  PairInfo info;
  for (std::size_t k = 0; k < block.size; ++k) {
    for (std::size_t c = 0; c < model.state_columns().size(); ++c) block.column[c][k] = 0;
    model.initialise(block, k, info);
    // Some pairs with a reference overlap, some with a shear force already stored.
    if (k % 3 == 0) block.column[kReferenceOverlap][k] = rng.uniform(-1e-5, 1e-5);
    if (k % 4 == 1)
      for (std::size_t c : {kShearX, kShearY, kShearZ}) block.column[c][k] = rng.uniform(-5, 5);
  }
  const std::size_t pairs = block.size, spheres = scene.s.size();
  std::vector<double> f(9 * pairs, 0.0), sums(6 * spheres, 0.0);
  PairForces out{&f[0], &f[pairs], &f[2 * pairs], &f[3 * pairs], &f[5 * pairs], &f[7 * pairs]};
  if (direct) {
    out.sum_fx = &sums[0], out.sum_fy = &sums[spheres], out.sum_fz = &sums[2 * spheres];
    out.sum_mx = &sums[3 * spheres], out.sum_my = &sums[4 * spheres], out.sum_mz = &sums[5 * spheres];
    out.i = block.i, out.j = block.j;
  }
  for (int step = 0; step < 10; ++step) model.sphere_forces(block, scene.s, out, {1e-5, 0});
  Outcome o;
  for (std::size_t c = 0; c < model.state_columns().size(); ++c)
    for (std::size_t k = 0; k < pairs; ++k) o.state.push_back(block.column[c][k]);
  o.forces = f;
  o.sums = sums;
  o.flags.assign(block.flags, block.flags + pairs);
  return o;
}

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(bits(a[k]), bits(b[k])) << what << " entry " << k;
}

}  // namespace

TEST(LinearBatch3D, TheSameBitsAsTheScalarLaw) {
  const ScalarLinear scalar(kParameters, "test");
  const BatchedLinear batched(kParameters, "test");
  for (const bool direct : {false, true})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Outcome a = run(scalar, seed, direct), b = run(batched, seed, direct);
      // The scene is what the test says it is: more pairs than a batch, some
      // touching, some apart, some sliding.
      ASSERT_GT(a.flags.size(), linear_batch::kBatch + 1);
      ASSERT_NE(a.flags.size() % linear_batch::kBatch, 0u) << a.flags.size() << " pairs";
      std::size_t touching = 0, sliding = 0;
      const std::size_t pairs = a.flags.size();
      for (std::size_t k = 0; k < pairs; ++k) {
        touching += (a.flags[k] & dem::kTouching) != 0;
        const double fs2 = a.state[kShearX * pairs + k] * a.state[kShearX * pairs + k] +
                           a.state[kShearY * pairs + k] * a.state[kShearY * pairs + k] +
                           a.state[kShearZ * pairs + k] * a.state[kShearZ * pairs + k];
        sliding += fs2 > 0 && (a.flags[k] & dem::kTouching) &&
                   std::abs(std::sqrt(fs2) - 0.3 * std::sqrt(a.forces[k] * a.forces[k] +
                                                             a.forces[pairs + k] * a.forces[pairs + k] +
                                                             a.forces[2 * pairs + k] * a.forces[2 * pairs + k] - fs2)) <
                       1e-9 * std::sqrt(fs2);
      }
      EXPECT_GT(touching, 10u);
      EXPECT_LT(touching, pairs - 2 * linear_batch::kBatch - 10);
      EXPECT_GT(sliding, 3u);
      expect_same_bits(a.state, b.state, "state");
      expect_same_bits(a.forces, b.forces, "forces");
      expect_same_bits(a.sums, b.sums, "sums");
      EXPECT_EQ(a.flags, b.flags);
    }
}
