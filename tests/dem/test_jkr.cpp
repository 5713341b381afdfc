// Closed-form checks of the JKR contact (jkr_model.cpp): pulled apart slowly,
// two disks stick until the pull reaches -1.5 pi w R* and let go at the end of
// the JKR curve; the contact forms only on touch (hysteresis); with no
// adhesion the model is Hertz-Mindlin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "../common/error_of.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "imposed_motion.hpp"

using namespace demcal::dem;

namespace {

constexpr double kRadius = 1e-3, kShearModulus = 3.5e7, kPoisson = 0.4;

nlohmann::json jkr(double work_of_adhesion_j_m2) {
  return {{"shear_modulus_pa", kShearModulus}, {"poisson", kPoisson},  {"restitution", 0.5},
          {"friction", 0.5},                  {"work_of_adhesion_j_m2", work_of_adhesion_j_m2}};
}

// Two fixed disks (no dashpot: fixed bodies have no moving mass) at centre
// distance 2 r - overlap; the test moves disk 1 along x.
World fixed_pair(double work_of_adhesion_j_m2, double overlap_m, double dt_s, double skin_m = 0.0) {
  WorldSettings settings;
  settings.skin_m = skin_m;
  settings.fixed_dt_s = dt_s;
  settings.damping = 0;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create("jkr", jkr(work_of_adhesion_j_m2), "test")));
  world.bodies.add_disk(0, 0, kRadius, 2650, 1, 0);
  world.bodies.add_disk(2 * kRadius - overlap_m, 0, kRadius, 2650, 1, 0);
  world.bodies.fixed[0] = world.bodies.fixed[1] = 1;
  return world;
}

const double kEffectiveModulus = kShearModulus / (1 - kPoisson), kEffectiveRadius = 0.5 * kRadius;

// The end of the JKR curve: delta(a_c), a_c = (pi w R*^2 / (8 E*))^(1/3).
double separation_limit(double w) {
  const double ac = std::cbrt(M_PI * w * kEffectiveRadius * kEffectiveRadius / (8 * kEffectiveModulus));
  return -(ac * ac / kEffectiveRadius - std::sqrt(2 * M_PI * w * ac / kEffectiveModulus));
}

}  // namespace

TEST(Jkr, PulledApartSlowlyItSticksUntilThePullOffForce) {
  const double w = 1.0;  // J/m^2
  const double limit = separation_limit(w);
  const double dt = 1e-6, steps_to_limit = 4000;
  World world = fixed_pair(w, 2e-7, dt);
  const double speed = (limit + 2e-7) / (steps_to_limit * dt);
  double least_force = 0, last_pull_gap = -1;
  for (int s = 0; s < 2 * steps_to_limit; ++s) {
    const double gap = (world.bodies.x[1] - world.bodies.x[0]) - 2 * kRadius;
    demcal::dem::testing::imposed_step(world, speed, 0, 0);
    least_force = std::min(least_force, world.bodies.fx[1]);  // the force on disk 1 along +x: < 0 pulls
    if (world.bodies.fx[1] < 0) last_pull_gap = gap;
  }
  const double pull_off = -1.5 * M_PI * w * kEffectiveRadius;
  EXPECT_NEAR(least_force, pull_off, 1e-4 * std::abs(pull_off));
  // It lets go at the end of the curve, to within one step's motion.
  EXPECT_NEAR(last_pull_gap, limit, 1.01 * speed * dt);
  EXPECT_GT(limit, 0.0);
  EXPECT_EQ(world.touching_pairs(), 0u);
}

// So strong an adhesion that the curve ends 0.39 R from touch, beyond the
// default skin of 0.25 R: the list must keep the pair that far (the skin then
// defaults to twice the model's largest delta_c). With the 0.25 R skin it left
// the list at the first build past 0.25 R and let go there.
TEST(Jkr, PulledPastAQuarterRadiusItStillHoldsUntilTheEndOfItsCurve) {
  const double w = 1e4;
  const double limit = separation_limit(w);
  ASSERT_GT(limit, 0.3 * kRadius);
  const double dt = 1e-6, steps_to_limit = 4000;
  World world = fixed_pair(w, 2e-7, dt);
  const double speed = (limit + 2e-7) / (steps_to_limit * dt);
  double last_pull_gap = -1;
  for (int s = 0; s < 1.5 * steps_to_limit; ++s) {
    const double gap = (world.bodies.x[1] - world.bodies.x[0]) - 2 * kRadius;
    demcal::dem::testing::imposed_step(world, speed, 0, 0);
    if (world.bodies.fx[1] < 0) last_pull_gap = gap;
  }
  EXPECT_NEAR(last_pull_gap, limit, 1.01 * speed * dt);
  EXPECT_GT(world.skin_m(), 2 * limit);  // 2 delta_c at R* = the disk's radius (a wall's pair)
  EXPECT_GT(world.rebuilds(), 1u);
}

TEST(Jkr, ASkinSetBelowTheEndOfTheCurveIsRefused) {
  const double w = 1e4;
  World world = fixed_pair(w, 2e-7, 1e-6, 0.25 * kRadius);
  const std::string message = demcal::test::error_of([&] { world.step(); });
  EXPECT_NE(message.find("the neighbour-list skin (0.00025 m) does not exceed the largest gap a contact model's pairs "
                         "pull across"),
            std::string::npos)
      << message;
  // Ordinary adhesion fits the same skin.
  World ordinary = fixed_pair(1.0, 2e-7, 1e-6, 0.25 * kRadius);
  EXPECT_EQ(demcal::test::error_of([&] { ordinary.step(); }), "");
}

TEST(Jkr, ContactFormsOnlyOnTouchAndSnapsIn) {
  const double w = 1.0;
  const double limit = separation_limit(w);
  // Approaching from a gap inside the curve's range: no force until touch.
  World world = fixed_pair(w, -0.5 * limit, 1e-6);
  world.step();
  EXPECT_EQ(world.bodies.fx[1], 0.0);
  EXPECT_EQ(world.touching_pairs(), 0u);
  // At touch (delta = 0: a^3 = 2 pi w R*^2 / E*) the contact forms, already pulling.
  World touching = fixed_pair(w, 0.0, 1e-6);
  touching.bodies.x[1] -= 1e-12;  // just touching
  touching.step();
  const double a3 = 2 * M_PI * w * kEffectiveRadius * kEffectiveRadius / kEffectiveModulus;
  const double expected = 4 * kEffectiveModulus * a3 / (3 * kEffectiveRadius) - std::sqrt(8 * M_PI * w * kEffectiveModulus * a3);
  EXPECT_LT(expected, 0.0);
  EXPECT_NEAR(touching.bodies.fx[1], expected, 1e-5 * std::abs(expected));  // delta is 1e-12 m, not 0
  // Pulled back to the same gap as before, it still holds (hysteresis).
  touching.bodies.x[1] += 0.5 * limit;
  touching.step();
  EXPECT_LT(touching.bodies.fx[1], 0.0);
  EXPECT_EQ(touching.touching_pairs(), 1u);
}

TEST(Jkr, WithoutAdhesionItIsHertzMindlin) {
  auto run = [](const std::string& model, nlohmann::json p) {
    WorldSettings settings;
    settings.damping = 0;
    settings.thickness_m = 1e-3;
    World world(settings);
    world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(model, p, "test")));
    world.bodies.add_disk(0, 0, kRadius, 2650, 1e-3, 0);
    world.bodies.add_disk(2 * kRadius + 1e-6, 1e-4, kRadius, 2650, 1e-3, 0);  // oblique: friction and spin too
    world.bodies.vx[0] = 0.1;
    world.bodies.vx[1] = -0.1;
    world.run(2000);
    return world;
  };
  nlohmann::json hertz = jkr(0.0);
  hertz.erase("work_of_adhesion_j_m2");
  World a = run("jkr", jkr(0.0)), b = run("hertz_mindlin", hertz);
  EXPECT_EQ(a.bodies.x, b.bodies.x);
  EXPECT_EQ(a.bodies.vx, b.bodies.vx);
  EXPECT_EQ(a.bodies.w, b.bodies.w);
  EXPECT_NE(a.bodies.w[0], 0.0);  // the oblique impact did spin them
}

TEST(Jkr, NegativeWorkOfAdhesionIsRefused) {
  const std::string message = demcal::test::error_of(
      [] { ContactModelRegistry::instance().create("jkr", jkr(-1.0), "powder.json: contacts.powder-powder"); });
  EXPECT_NE(message.find("powder.json: contacts.powder-powder: work_of_adhesion_j_m2 must be >= 0"), std::string::npos)
      << message;
}
