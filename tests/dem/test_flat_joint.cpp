// A single flat joint (Potyondy 2012, 2D) against closed forms: an intact
// joint pulls and bends like a parallel bond of the same geometry; bending
// breaks it element by element from the opening side, and the damaged joint
// still resists rotation with the elements it presses; its shear strength
// grows with the normal stress (c + sigma tan phi_b), and broken elements
// slide on Coulomb friction.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/world.hpp"
#include "imposed_motion.hpp"

using namespace demcal::dem;
using demcal::dem::testing::imposed_step;

namespace {

constexpr double kRadius = 1e-3, kDt = 1e-8;
constexpr double kJointModulus = 2e9, kJointKnKs = 2.0;
// kn = E_j / (R_i + R_j) per area; A = 2 R t with t = 1; I = 2/3 R^3.
constexpr double kKn = kJointModulus / (2 * kRadius);
constexpr double kKs = kKn / kJointKnKs;
constexpr double kArea = 2 * kRadius;
constexpr double kInertia = 2.0 / 3.0 * kRadius * kRadius * kRadius;

World joined_pair(int elements, double sigma_c, double cohesion, double phi_deg = 0, double mu = 0.5) {
  return demcal::dem::testing::bonded_fixed_pair(
      "flat_joint",
      {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}, {"joint_modulus_pa", kJointModulus},
       {"joint_kn_ks", kJointKnKs}, {"elements", elements}, {"tensile_strength_pa", sigma_c}, {"cohesion_pa", cohesion},
       {"friction_angle_deg", phi_deg}, {"joint_friction", mu}},
      kRadius, kDt);
}

}  // namespace

TEST(FlatJoint, TensionIsKnADeltaAndEveryElementBreaksAtTheTensileStrength) {
  const double sigma_c = 1e7, v = 1.0;
  World world = joined_pair(3, sigma_c, 1e9);
  int steps = 0;
  double last_force = 0;
  while (world.breaks().empty() && steps < 5000) {
    imposed_step(world, v, 0, 0);
    ++steps;
    if (world.breaks().empty()) {
      last_force = world.bodies.fx[0];
      ASSERT_NEAR(last_force, kKn * kArea * v * kDt * steps, 1e-9 * kKn * kArea * v * kDt * steps);
    }
  }
  ASSERT_EQ(world.breaks().size(), 3u);  // a uniform pull breaks the three elements at once
  for (const BreakEvent& e : world.breaks()) EXPECT_EQ(e.mode, BreakMode::Tension);
  EXPECT_LT(last_force, sigma_c * kArea);
  EXPECT_GE(last_force + kKn * kArea * v * kDt, sigma_c * kArea * (1 - 1e-12));
  EXPECT_FALSE(world.pairs().flags[0] & kBonded);
  imposed_step(world, v, 0, 0);
  EXPECT_EQ(world.bodies.fx[0], 0.0);  // open faces carry nothing
  // Pushed back past where they were joined, the broken faces carry compression only.
  for (int s = 0; s < 2 * steps + 10; ++s) imposed_step(world, -v, 0, 0);
  EXPECT_GT(world.bodies.fx[1], 0.0);
}

TEST(FlatJoint, AnIntactJointBendsLikeAParallelBondWhateverItsElements) {
  // Each element carries its centre force and its own moment: sum(A_e x_e^2 + I_e) = I exactly.
  const double w = 100.0;
  for (int elements : {1, 2, 5}) {
    World world = joined_pair(elements, 1e12, 1e12);
    for (int s = 1; s <= 50; ++s) {
      imposed_step(world, 0, 0, w);
      const double theta = 2 * w * kDt * s;
      ASSERT_NEAR(world.bodies.moment[1], -kKn * kInertia * theta, 1e-9 * kKn * kInertia * theta) << elements;
      ASSERT_NEAR(world.bodies.fx[0], 0.0, 1e-9 * kKn * kArea * kRadius * theta);  // pure bending
    }
  }
}

TEST(FlatJoint, BendingBreaksItElementByElementAndTheDamagedJointStillResistsRotation) {
  // Four elements, centres at x = -3R/4, -R/4, R/4, 3R/4. A rotation theta
  // opens the elements at x < 0 by -x theta: the outer one breaks at theta1 =
  // sigma_c / (kn 3R/4), the inner at theta2 = sigma_c / (kn R/4). Beyond
  // that the elements at x > 0 (pressed, bonded) carry M = -kn theta
  // sum_{x > 0} (A_e x^2 + I_e), which a broken parallel bond would not.
  const double sigma_c = 1e6, w = 100.0, width = kRadius / 2, area_e = width, inertia_e = width * width * width / 12;
  World world = joined_pair(4, sigma_c, 1e12);
  const double theta1 = sigma_c / (kKn * 0.75 * kRadius), theta2 = sigma_c / (kKn * 0.25 * kRadius);
  const double dtheta = 2 * w * kDt;
  int steps = 0, first = 0;
  while (world.breaks().size() < 2 && steps < 1000000) {
    imposed_step(world, 0, 0, w);
    ++steps;
    if (world.breaks().size() == 1 && first == 0) first = steps;
  }
  EXPECT_NEAR(first * dtheta, theta1, dtheta);
  ASSERT_EQ(world.breaks().size(), 2u);
  EXPECT_NEAR(steps * dtheta, theta2, dtheta);
  for (int s = 0; s < 1000; ++s) imposed_step(world, 0, 0, w);
  const double theta = (steps + 1000) * dtheta;
  const double pressed = area_e * (0.25 * kRadius) * (0.25 * kRadius) + area_e * (0.75 * kRadius) * (0.75 * kRadius) +
                         2 * inertia_e;
  EXPECT_NEAR(world.bodies.moment[1], -kKn * theta * pressed, 1e-9 * kKn * theta * pressed);
  EXPECT_EQ(world.breaks().size(), 2u);  // the pressed side never fails in tension
  EXPECT_TRUE(world.pairs().flags[0] & kBonded);
}

TEST(FlatJoint, ShearStrengthGrowsWithTheNormalStressAndBrokenElementsSlideOnFriction) {
  // Pressed by delta: sigma_n = kn delta; then sheared: every element breaks
  // when |F_s| / A reaches c + sigma_n tan(phi_b); afterwards |F_s| = mu F_n.
  const double cohesion = 2e6, phi = 30.0, mu = 0.4, v = 1.0;
  World world = joined_pair(2, 1e12, cohesion, phi, mu);
  const int press = 200;
  for (int s = 0; s < press; ++s) imposed_step(world, -v, 0, 0);
  EXPECT_NEAR(world.pair_state(0, "element1_gap_m"), -v * kDt * press, 1e-12 * v * kDt * press);
  // Checked on the elements' own state (the shear slightly turns the normal
  // and opens the joint, by about 0.5 % of the press here).
  const double tan_phi = std::tan(phi * M_PI / 180), area_e = kArea / 2;
  double last_shear = 0, last_strength = 0;
  int steps = 0;
  while (world.breaks().empty() && steps < 100000) {
    imposed_step(world, 0, v, 0);
    ++steps;
    if (world.breaks().empty()) {
      last_shear = std::abs(world.pair_state(0, "element1_shear_force_n"));
      last_strength = area_e * (cohesion - kKn * world.pair_state(0, "element1_gap_m") * tan_phi);
    }
  }
  ASSERT_EQ(world.breaks().size(), 2u);
  for (const BreakEvent& e : world.breaks()) EXPECT_EQ(e.mode, BreakMode::Shear);
  const double increment = kKs * area_e * v * kDt;
  EXPECT_LT(last_shear, last_strength);
  EXPECT_GT(last_shear + 1.01 * increment, last_strength);
  EXPECT_GT(last_strength, 1.3 * area_e * cohesion);  // the press added its sigma_n tan(phi_b)
  for (int s = 0; s < 100; ++s) imposed_step(world, 0, v, 0);
  for (const char* e : {"element1", "element2"}) {
    const double normal = -kKn * area_e * world.pair_state(0, std::string(e) + "_gap_m");
    EXPECT_NEAR(std::abs(world.pair_state(0, std::string(e) + "_shear_force_n")), mu * normal, 1e-9 * normal) << e;
  }
}

TEST(FlatJoint, BadParametersAreRefusedWithTheField) {
  nlohmann::json p = {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}, {"joint_modulus_pa", 1e9},
                      {"joint_kn_ks", 2.0}, {"tensile_strength_pa", 1e6}, {"cohesion_pa", 1e6},
                      {"friction_angle_deg", 30}, {"joint_friction", 0.5}};
  EXPECT_NO_THROW(ContactModelRegistry::instance().create("flat_joint", p, "s.json: contacts.particle-particle"));
  for (auto [key, value] : std::vector<std::pair<std::string, double>>{{"elements", 7}, {"elements", 2.5},
                                                                       {"friction_angle_deg", 90}, {"cohesion_pa", -1}}) {
    nlohmann::json bad = p;
    bad[key] = value;
    try {
      ContactModelRegistry::instance().create("flat_joint", bad, "s.json: contacts.particle-particle");
      ADD_FAILURE() << key << " " << value;
    } catch (const demcal::Error& e) {
      EXPECT_NE(std::string(e.what()).find("s.json: contacts.particle-particle"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(FlatJoint, ALockedInStressIsRefusedNamingTheField) {
  // Its joints are installed force-free: a locked-in stress would silently not be there.
  nlohmann::json scene = Scene::resolved_json(std::string(DEMCAL_SOURCE_DIR) + "/data/scenes/ucs_rock_fj.json");
  scene["specimen"]["width_m"] = 0.01;
  scene["specimen"]["height_m"] = 0.02;
  scene["specimen"]["locked_in_stress_pa"] = 1e6;
  const Scene s = Scene::from_json(scene, "fj.json");
  RunOptions options;
  options.cache_dir = "";
  try {
    run_test(s, s.resolve({}), options);
    ADD_FAILURE() << "no error";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("fj.json: specimen.locked_in_stress_pa: not supported with the flat_joint"),
              std::string::npos) << e.what();
  }
}

// A broken element presses where its faces overlap, and the overlap varies as
// gap - theta u across it: so one element, fully broken in shear under a
// press, still resists rotation, as the intact joint's -kn I theta while it is
// pressed all across (before, a broken element pushed at its centre only and
// the joint turned freely).
TEST(FlatJoint, AFullyBrokenElementStillResistsRotationWhereItIsPressed) {
  const double v = 1.0, w = 100.0;
  World world = joined_pair(1, 1e12, 1e3);  // a cohesion that the first shear breaks
  const int press = 200;
  for (int s = 0; s < press; ++s) imposed_step(world, -v, 0, 0);
  imposed_step(world, 0, v, 0);
  ASSERT_EQ(world.breaks().size(), 1u);
  ASSERT_FALSE(world.pairs().flags[0] & kBonded);
  const double gap = world.pair_state(0, "element1_gap_m");
  ASSERT_LT(gap, 0.0);
  // The sliding shear force's own moment (F_s R on each disk) stays as it is while the disks roll on each other:
  // the joint's couple is what the rotation adds to it.
  imposed_step(world, 0, 0, 0);
  const double before = world.bodies.moment[1];
  // Turn it by less than the press: the faces stay pressed all across (|theta| R < |gap|).
  for (int s = 1; s <= 20; ++s) {
    imposed_step(world, 0, 0, w);
    const double theta = world.pair_state(0, "joint_rotation_rad");
    ASSERT_LT(std::abs(theta) * kRadius, -gap);
    ASSERT_NEAR(world.bodies.moment[1] - before, -kKn * kInertia * theta, 1e-6 * kKn * kInertia * std::abs(theta)) << s;
  }
  // Turned further, only the pressed part carries: less than the full moment, more than none.
  for (int s = 0; s < 2000; ++s) imposed_step(world, 0, 0, w);
  const double theta = world.pair_state(0, "joint_rotation_rad");
  ASSERT_GT(std::abs(theta) * kRadius, -gap);
  const double couple = std::abs(world.bodies.moment[1] - before);
  EXPECT_LT(couple, kKn * kInertia * std::abs(theta));
  EXPECT_GT(couple, 0.1 * kKn * kInertia * (-gap / kRadius));
}

// One law for a fully broken joint: once its faces have parted it is a linear
// contact (the modulus_pa, kn_ks and friction of pairs that meet later), at
// once, not only after the neighbour list has dropped it (which depended on the skin).
TEST(FlatJoint, AFullyBrokenJointWhoseFacesPartIsALinearContactAtOnce) {
  const double v = 1.0;
  World world = joined_pair(2, 1e7, 1e12);
  int steps = 0;
  while (world.breaks().size() < 2 && steps < 5000) {
    imposed_step(world, v, 0, 0);
    ++steps;
  }
  ASSERT_EQ(world.breaks().size(), 2u);
  imposed_step(world, v, 0, 0);
  EXPECT_EQ(world.pair_state(0, "joint"), 0.0);
  // Pushed back past where they were joined: the linear contact's kn (E t for equal disks of t = 1) times the
  // overlap, not the joint's kn_j A.
  for (int s = 0; s < steps + 1 + 100; ++s) imposed_step(world, -v, 0, 0);
  imposed_step(world, 0, 0, 0);
  const double overlap = 2 * kRadius - (world.bodies.x[1] - world.bodies.x[0]);
  ASSERT_GT(overlap, 0.0);
  EXPECT_NEAR(world.bodies.fx[1], 1e9 * overlap, 1e-6 * 1e9 * overlap);
}

// A zero strength is none: the element holds at rest and breaks at its first tension.
TEST(FlatJoint, AZeroStrengthBreaksAtTheFirstTensionNotAtRest) {
  World world = joined_pair(2, 0.0, 0.0);
  for (int s = 0; s < 10; ++s) imposed_step(world, 0, 0, 0);
  EXPECT_TRUE(world.breaks().empty());
  EXPECT_TRUE(world.pairs().flags[0] & kBonded);
  imposed_step(world, 1.0, 0, 0);
  imposed_step(world, 1.0, 0, 0);
  EXPECT_EQ(world.breaks().size(), 2u);
}
