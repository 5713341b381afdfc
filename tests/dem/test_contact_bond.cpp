// The contact bond against its closed form: linear in tension and shear while
// bonded, broken when the force reaches strength x 2 min(R) t (PFC's contact
// area, as its cb_strength uses it), then a frictional contact.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "imposed_motion.hpp"

using namespace demcal::dem;
using demcal::dem::testing::imposed_step;

namespace {

constexpr double kR1 = 1e-3, kR2 = 1.5e-3, kDt = 1e-8, kModulus = 1e9, kKnKs = 2.5;
// kn = A E / L with A = 2 min(R) t, L = R1 + R2; strengths as forces: stress x A
// (unequal radii, so the mean radius's 2.5 mm would not pass).
constexpr double kKn = 2 * kR1 * kModulus / (kR1 + kR2);
constexpr double kWidth = 2 * kR1;

// Two fixed disks `gap` apart, glued by a contact bond.
World bonded_pair(double sigma_c, double tau_c, double gap = 0.0) {
  WorldSettings settings;
  settings.fixed_dt_s = kDt;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(
                        "contact_bond",
                        {{"modulus_pa", kModulus}, {"kn_ks", kKnKs}, {"friction", 0.3},
                         {"tensile_strength_pa", sigma_c}, {"shear_strength_pa", tau_c}},
                        "test")));
  world.bodies.add_disk(0, 0, kR1, 2650, 1, 0);
  world.bodies.add_disk(kR1 + kR2 + gap, 0, kR2, 2650, 1, 0);
  world.bodies.fixed[0] = world.bodies.fixed[1] = 1;
  EXPECT_EQ(world.install_bonds(gap + 1e-9, 1), 1u);
  return world;
}

// Slides disk 1 along y at v until the bond breaks (at most 100,000 steps); the steps taken.
int shear_until_break(World& world, double v) {
  int steps = 0;
  while (world.breaks().empty() && steps < 100000) {
    imposed_step(world, 0, v, 0);
    ++steps;
  }
  return steps;
}

}  // namespace

TEST(ContactBond, TensionIsKnDeltaUntilTheNormalStrengthForce) {
  const double sigma_c = 2e6, v = 1.0;
  World world = bonded_pair(sigma_c, 1e9);
  double last = 0;
  int steps = 0;
  while (world.breaks().empty() && steps < 100000) {
    imposed_step(world, v, 0, 0);
    ++steps;
    // The force follows the gap of the positions the step started from.
    if (world.breaks().empty()) {
      last = world.bodies.fx[0];
      ASSERT_NEAR(last, kKn * v * kDt * (steps - 1), 1e-9 * kKn * v * kDt * steps + 1e-12);
    }
  }
  ASSERT_EQ(world.breaks().size(), 1u);
  EXPECT_EQ(world.breaks()[0].mode, BreakMode::Tension);
  EXPECT_LT(last, sigma_c * kWidth);
  EXPECT_GE(last + 1.000001 * kKn * v * kDt, sigma_c * kWidth);
  EXPECT_EQ(world.bodies.fx[0], 0.0);  // broken, apart: no force
}

TEST(ContactBond, ShearBreaksAtTheShearStrengthThenSlidesWithFriction) {
  const double tau_c = 1e5, v = 1.0, ks = kKn / kKnKs;
  World world = bonded_pair(1e9, tau_c);
  // A small overlap so friction has a normal force afterwards: mu Fn = 0.3 x 400 N, below the 200 N the bond held.
  world.bodies.x[1] -= 0.5e-6;
  world.refresh();
  const int steps = shear_until_break(world, v);
  ASSERT_EQ(world.breaks().size(), 1u);
  EXPECT_EQ(world.breaks()[0].mode, BreakMode::Shear);
  EXPECT_NEAR(ks * v * kDt * steps, tau_c * kWidth, 1.01 * ks * v * kDt);
  // After the break the shear force is capped at mu * Fn.
  imposed_step(world, 0, v, 0);
  EXPECT_NEAR(std::abs(world.pair_state(0, "shear_force_n")), 0.3 * kKn * 0.5e-6, 1e-3 * 0.3 * kKn * 0.5e-6);
}

TEST(ContactBond, UtilisationIsTheBreakTestsForceOverItsStrength) {
  // Tension: kn delta against sigma_c A; shear: ks delta against tau_c A.
  const double sigma_c = 1e7, tau_c = 4e6, v = 1.0, ks = kKn / kKnKs;
  World pulled = bonded_pair(sigma_c, 1e9);
  EXPECT_EQ(pulled.max_bond_utilisation(), 0.0);
  for (int s = 0; s < 30; ++s) imposed_step(pulled, v, 0, 0);
  const double tension = kKn * v * kDt * 30 / (sigma_c * kWidth);
  EXPECT_NEAR(pulled.max_bond_utilisation(), tension, 1e-6 * tension);

  World sheared = bonded_pair(1e9, tau_c);
  for (int s = 0; s < 30; ++s) imposed_step(sheared, 0, v, 0);
  const double shear = ks * v * kDt * 30 / (tau_c * kWidth);
  EXPECT_NEAR(sheared.max_bond_utilisation(), shear, 1e-5 * shear);
  shear_until_break(sheared, v);
  ASSERT_EQ(sheared.breaks().size(), 1u);
  EXPECT_EQ(sheared.max_bond_utilisation(), 0.0);  // no bond left intact
}

TEST(ContactBond, ABondInstalledAcrossAGapStartsFreeOfForce) {
  World world = bonded_pair(1e6, 1e6, 1e-6);  // a 1 um gap
  imposed_step(world, 0, 0, 0);
  EXPECT_EQ(world.bodies.fx[0], 0.0);
  EXPECT_TRUE(world.breaks().empty());
  // Pulled 1 um further, it carries kn x 1 um of tension.
  for (int s = 0; s < 100; ++s) imposed_step(world, 1e-6 / (100 * kDt), 0, 0);
  imposed_step(world, 0, 0, 0);
  EXPECT_NEAR(world.bodies.fx[0], kKn * 1e-6, 1e-6 * kKn * 1e-6);
}

// PFC's linearcbond: a bond that fails in shear leaves this step's forces as
// they are, so the shear force carries one increment per step (not two on the
// breaking step), and the Coulomb limit applies from the next step.
TEST(ContactBond, TheBreakingStepAddsTheShearIncrementOnce) {
  const double tau_c = 1e5, v = 1.0, ks = kKn / kKnKs;
  World world = bonded_pair(1e9, tau_c);
  world.bodies.x[1] -= 1e-5;  // pressed: mu Fn = 0.3 x 8000 N stays far above the 200 N shear strength force
  world.refresh();
  const int steps = shear_until_break(world, v);
  ASSERT_EQ(world.breaks().size(), 1u);
  EXPECT_EQ(world.breaks()[0].mode, BreakMode::Shear);
  EXPECT_NEAR(std::abs(world.pair_state(0, "shear_force_n")), ks * v * kDt * steps, 1e-6 * ks * v * kDt * steps);
  // The normal force stands too (the shear motion tilts the normal by about 3e-4 rad).
  EXPECT_NEAR(world.bodies.fx[0], -kKn * 1e-5, 1e-4 * kKn * 1e-5);
}

// A bond glued across a gap keeps that gap as its reference when it breaks:
// pressed half-way shut, the pair carries kn x (half the gap) before and after
// a shear break, where forgetting the reference would drop it to zero.
TEST(ContactBond, ABrokenBondKeepsTheGapItWasGluedAcross) {
  const double gap = 1e-6, tau_c = 1e5, v = 1.0;
  World world = bonded_pair(1e9, tau_c, gap);
  world.bodies.x[1] -= 0.5 * gap;
  world.refresh();
  imposed_step(world, 0, 0, 0);
  EXPECT_NEAR(world.bodies.fx[0], -kKn * 0.5 * gap, 1e-6 * kKn * gap);  // bonded, compressed
  // Tolerance below: the shear motion tilts the normal by about 3e-4 rad.
  const int steps = shear_until_break(world, v);
  ASSERT_LT(steps, 100000) << "the bond never broke";
  ASSERT_EQ(world.breaks().size(), 1u);
  ASSERT_EQ(world.breaks()[0].mode, BreakMode::Shear);
  for (int s = 0; s < 3; ++s) {
    imposed_step(world, 0, 0, 0);
    EXPECT_NEAR(world.bodies.fx[0], -kKn * 0.5 * gap, 1e-3 * kKn * 0.5 * gap) << "step " << s << " after the break";
    // Sliding is now limited by friction on that normal force.
    EXPECT_LE(std::abs(world.pair_state(0, "shear_force_n")), 0.3 * kKn * 0.5 * gap * (1 + 1e-12));
  }
  // Opened past the reference gap, it lets go.
  for (int s = 0; s < 100; ++s) imposed_step(world, gap / (100 * kDt), 0, 0);
  imposed_step(world, 0, 0, 0);
  EXPECT_EQ(world.bodies.fx[0], 0.0);
}
