// A single parallel bond against its closed form (Potyondy & Cundall 2004):
// force = k A delta in tension and shear, moment = k I theta in bending, and
// the bond breaks when the stress first reaches its strength.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "imposed_motion.hpp"

using namespace demcal::dem;
using demcal::dem::testing::imposed_step;

namespace {

constexpr double kRadius = 1e-3, kDt = 1e-8;
constexpr double kBondModulus = 2e9, kBondKnKs = 2.0;
// kn_b = E_b / (R_i + R_j); A = 2 R_b t; I = 2/3 R_b^3 t with R_b = R, t = 1.
constexpr double kKnBond = kBondModulus / (2 * kRadius);
constexpr double kKsBond = kKnBond / kBondKnKs;
constexpr double kArea = 2 * kRadius;
constexpr double kInertia = 2.0 / 3.0 * kRadius * kRadius * kRadius;

// Two touching disks held by a parallel bond; the test prescribes their motion.
World bonded_pair(double sigma_c, double tau_c) {
  return demcal::dem::testing::bonded_fixed_pair(
      "parallel_bond",
      {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}, {"bond_modulus_pa", kBondModulus},
       {"bond_kn_ks", kBondKnKs}, {"tensile_strength_pa", sigma_c}, {"shear_strength_pa", tau_c}},
      kRadius, kDt);
}

}  // namespace

TEST(ParallelBond, TensionForceIsKnADeltaAndBreaksAtTheTensileStrength) {
  const double sigma_c = 1e7, v = 1.0;
  World world = bonded_pair(sigma_c, 1e9);
  int steps = 0;
  double last_force = 0;
  while (world.breaks().empty() && steps < 5000) {
    imposed_step(world, v, 0, 0);
    ++steps;
    if (world.breaks().empty()) {
      const double delta = v * kDt * steps;
      last_force = world.bodies.fx[0];  // disk 0 is pulled towards disk 1
      ASSERT_NEAR(last_force, kKnBond * kArea * delta, 1e-9 * kKnBond * kArea * delta);
    }
  }
  ASSERT_EQ(world.breaks().size(), 1u);
  EXPECT_EQ(world.breaks()[0].mode, BreakMode::Tension);
  const double increment = kKnBond * kArea * v * kDt;
  EXPECT_LT(last_force, sigma_c * kArea);                 // intact below the strength
  EXPECT_GE(last_force + increment, sigma_c * kArea * (1 - 1e-12));  // broken on reaching it
  // Logged at the contact point: the middle of the gap, as it was when the
  // forces of the breaking step were computed (before that step's move).
  EXPECT_NEAR(world.breaks()[0].x_m, kRadius + 0.5 * v * kDt * (steps - 1), 1e-12);
  imposed_step(world, v, 0, 0);
  EXPECT_EQ(world.bodies.fx[0], 0.0);  // a broken bond in tension carries nothing
}

TEST(ParallelBond, ShearForceIsKsADeltaAndBreaksAtTheShearStrength) {
  const double tau_c = 2e6, v = 1.0;
  World world = bonded_pair(1e9, tau_c);
  int steps = 0;
  double last_shear = 0;
  while (world.breaks().empty() && steps < 5000) {
    imposed_step(world, 0, v, 0);
    ++steps;
    if (world.breaks().empty()) {
      last_shear = std::abs(world.pair_state(0, "bond_shear_force_n"));
      const double delta = v * kDt * steps;
      // The normal turns by delta / 2R (< 2e-3 rad here): agreement to 1e-5.
      ASSERT_NEAR(last_shear, kKsBond * kArea * delta, 1e-5 * kKsBond * kArea * delta);
      ASSERT_NEAR(world.bodies.fy[0], kKsBond * kArea * delta, 1e-5 * kKsBond * kArea * delta);
    }
  }
  ASSERT_EQ(world.breaks().size(), 1u);
  EXPECT_EQ(world.breaks()[0].mode, BreakMode::Shear);
  EXPECT_LT(last_shear, tau_c * kArea);
  EXPECT_GE(last_shear + 1.001 * kKsBond * kArea * v * kDt, tau_c * kArea);
}

TEST(ParallelBond, BendingMomentIsKnITheta) {
  const double w = 100.0;  // each disk spins, in opposite senses
  World world = bonded_pair(1e9, 1e9);
  for (int s = 1; s <= 100; ++s) {
    imposed_step(world, 0, 0, w);
    const double theta = 2 * w * kDt * s;  // relative rotation
    ASSERT_NEAR(world.bodies.moment[1], -kKnBond * kInertia * theta, 1e-9 * kKnBond * kInertia * theta);
    ASSERT_NEAR(world.bodies.moment[0], kKnBond * kInertia * theta, 1e-9 * kKnBond * kInertia * theta);
    ASSERT_NEAR(world.bodies.fx[0], 0.0, 1e-9);  // pure bending: no net force
  }
}

TEST(ParallelBond, BendingBreaksInTensionAtSigmaC) {
  // sigma = |M| R_b / I = kn_b theta R_b reaches sigma_c at theta = sigma_c / (kn_b R_b).
  const double sigma_c = 1e6, w = 100.0;
  World world = bonded_pair(sigma_c, 1e9);
  int steps = 0;
  while (world.breaks().empty() && steps < 100000) {
    imposed_step(world, 0, 0, w);
    ++steps;
  }
  ASSERT_EQ(world.breaks().size(), 1u);
  EXPECT_EQ(world.breaks()[0].mode, BreakMode::Tension);
  const double theta_break = sigma_c / (kKnBond * kRadius);
  EXPECT_NEAR(2 * w * kDt * steps, theta_break, 2 * w * kDt);
}

TEST(ParallelBond, UtilisationIsTheBreakTestsStressOverItsStrength) {
  // Tension: sigma = kn_b delta against sigma_c; bending: |M| R_b / I = kn_b theta R_b;
  // shear: tau = ks_b delta against tau_c (the normal turns by delta / 2R: 1e-5).
  const double sigma_c = 1e7, tau_c = 4e6, v = 1.0, w = 100.0;
  World pulled = bonded_pair(sigma_c, 1e9);
  EXPECT_EQ(pulled.max_bond_utilisation(), 0.0);  // installed force-free
  int steps = 0;
  for (; steps < 30; ++steps) imposed_step(pulled, v, 0, 0);
  const double tension = kKnBond * v * kDt * steps / sigma_c;
  EXPECT_NEAR(pulled.max_bond_utilisation(), tension, 1e-9 * tension);
  while (pulled.breaks().empty() && steps < 5000) {
    imposed_step(pulled, v, 0, 0);
    ++steps;
    if (pulled.breaks().empty()) {
      ASSERT_LT(pulled.max_bond_utilisation(), 1.0);  // every bond that held
    }
  }
  ASSERT_EQ(pulled.breaks().size(), 1u);
  EXPECT_EQ(pulled.max_bond_utilisation(), 0.0);  // no bond left intact

  World bent = bonded_pair(sigma_c, 1e9);
  for (int s = 0; s < 20; ++s) imposed_step(bent, 0, 0, w);
  const double bending = kKnBond * 2 * w * kDt * 20 * kRadius / sigma_c;
  EXPECT_NEAR(bent.max_bond_utilisation(), bending, 1e-9 * bending);

  World sheared = bonded_pair(1e9, tau_c);
  for (int s = 0; s < 20; ++s) imposed_step(sheared, 0, v, 0);
  const double shear = kKsBond * v * kDt * 20 / tau_c;
  EXPECT_NEAR(sheared.max_bond_utilisation(), shear, 1e-5 * shear);

  // A zero strength breaks at the first test, loaded or not (tau >= 0).
  World weak = bonded_pair(sigma_c, 0.0);
  EXPECT_EQ(weak.max_bond_utilisation(), INFINITY);
  imposed_step(weak, 0, 0, 0);
  EXPECT_EQ(weak.breaks().size(), 1u);
  EXPECT_EQ(weak.max_bond_utilisation(), 0.0);
}

TEST(ParallelBond, AWorldWithoutBondsReportsNoUtilisation) {
  World world;
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(
                        "linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}}, "test")));
  world.bodies.add_disk(0, 0, kRadius, 2650, 1, 0);
  world.bodies.add_disk(1.9 * kRadius, 0, kRadius, 2650, 1, 0);  // touching: a listed pair
  world.refresh();
  ASSERT_EQ(world.pairs().size(), 1u);
  EXPECT_TRUE(std::isnan(world.max_bond_utilisation()));
}

TEST(ParallelBond, ABondKeepsItsPairBeyondTheSkin) {
  World world = bonded_pair(1e12, 1e12);
  world.bodies.x[1] += 3 * kRadius;  // far beyond the skin
  world.refresh();
  ASSERT_EQ(world.pairs().size(), 1u);
  EXPECT_TRUE(world.pairs().flags[0] & kBonded);
}
