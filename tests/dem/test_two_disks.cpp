// Closed-form checks of the linear contact: a head-on collision of two disks
// lasts pi sqrt(m_eff / kn) and, without damping, returns every joule.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"

using namespace demcal::dem;

namespace {

World two_disk_world(double speed_m_s, double safety) {
  WorldSettings settings;
  settings.damping = 0.0;
  settings.safety_factor = safety;
  World world(settings);
  auto model = ContactModelRegistry::instance().create(
      "linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}}, "test");
  world.assign(0, 0, world.add_model(std::move(model)));
  world.bodies.add_disk(0.0, 0.0, 1e-3, 2650, 1.0, 0);
  world.bodies.add_disk(2.05e-3, 0.0, 1e-3, 2650, 1.0, 0);
  world.bodies.vx[0] = speed_m_s / 2;
  world.bodies.vx[1] = -speed_m_s / 2;
  return world;
}

}  // namespace

TEST(TwoDisks, HeadOnContactLastsHalfAPeriodAndConservesEnergy) {
  World world = two_disk_world(0.1, 0.02);
  // kn = A E / L = (2 r t) E / (2 r) = E t = 1e9 N/m; m_eff = m / 2.
  const double kn = 1e9;
  const double m = 2650 * M_PI * 1e-6;
  const double expected_duration = M_PI * std::sqrt(0.5 * m / kn);
  const double energy_before = world.kinetic_energy();
  bool started = false, ended = false;
  double t_start = 0, t_end = 0;
  for (int s = 0; s < 200000 && !ended; ++s) {
    world.step();
    bool touching = world.touching_pairs() > 0;
    if (touching && !started) {
      started = true;
      t_start = world.time_s() - world.dt_s();  // forces first acted in this step
    }
    if (started && !touching) {
      ended = true;
      t_end = world.time_s() - world.dt_s();
    }
  }
  ASSERT_TRUE(ended);
  // Contact is detected to within one time step at each end.
  EXPECT_NEAR(t_end - t_start, expected_duration, 2 * world.dt_s());
  EXPECT_LT(2 * world.dt_s(), 0.02 * expected_duration);  // so the check is tight (2 %)
  EXPECT_NEAR(world.kinetic_energy(), energy_before, 1e-4 * energy_before);
  EXPECT_NEAR(world.bodies.vx[0], -0.05, 1e-4 * 0.05);  // velocities swap sign
  EXPECT_NEAR(world.bodies.vx[1], 0.05, 1e-4 * 0.05);
  EXPECT_NEAR(world.bodies.vy[0], 0.0, 1e-15);
}

TEST(TwoDisks, LocalDampingRemovesEnergy) {
  World world = two_disk_world(0.1, 0.1);
  world.settings().damping = 0.7;
  const double energy_before = world.kinetic_energy();
  world.run(20000);
  EXPECT_LT(world.kinetic_energy(), 0.2 * energy_before);
}

TEST(TwoDisks, SameInputsGiveTheSameBits) {
  World a = two_disk_world(0.3, 0.5), b = two_disk_world(0.3, 0.5);
  a.run(3000);
  b.run(3000);
  EXPECT_EQ(a.bodies.x, b.bodies.x);
  EXPECT_EQ(a.bodies.vx, b.bodies.vx);
}

TEST(TwoDisks, DiskBouncesOffAWallWithTheDeformabilityStiffness) {
  WorldSettings settings;
  settings.damping = 0.0;
  settings.safety_factor = 0.02;
  World world(settings);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                        "linear", {{"modulus_pa", 1e9}, {"kn_ks", 1.0}, {"friction", 0.0}}, "test")));
  world.bodies.add_disk(0.0, 1.05e-3, 1e-3, 2650, 1.0, 0);
  world.bodies.vy[0] = -0.1;
  Wall floor;
  floor.x0 = -1;
  floor.x1 = 1;
  floor.group = 1;
  world.walls.push_back(floor);
  // Disk-wall: kn = A E / L with A = 2 r t and L = r: 2 E t.
  const double kn = 2e9, m = 2650 * M_PI * 1e-6;
  double peak_push = 0, peak_pull = 0;
  for (int s = 0; s < 100000 && world.bodies.vy[0] < 0.0999; ++s) {
    world.step();
    peak_push = std::max(peak_push, -world.walls[0].fy);  // the disk pushes the floor down
    peak_pull = std::max(peak_pull, world.walls[0].fy);
  }
  EXPECT_NEAR(world.bodies.vy[0], 0.1, 1e-4);
  // Peak force of an elastic impact on a spring: v sqrt(k m), here within 1 %.
  EXPECT_NEAR(peak_push, 0.1 * std::sqrt(kn * m), 0.01 * 0.1 * std::sqrt(kn * m));
  EXPECT_EQ(peak_pull, 0.0);  // an unbonded contact never pulls
}

TEST(TwoDisks, DensityScalingRaisesMassesToReachTheRequestedStep) {
  World plain = two_disk_world(0.1, 0.8);
  plain.step();
  const double natural_dt = plain.dt_s();
  World scaled = two_disk_world(0.1, 0.8);
  scaled.settings().density_scaling_dt_s = 10 * natural_dt;
  const double mass_before = scaled.bodies.mass[0];
  scaled.step();
  EXPECT_NEAR(scaled.dt_s(), 10 * natural_dt, 1e-12 * natural_dt);
  // The step grows with sqrt(m): the mass grows 100-fold.
  EXPECT_NEAR(scaled.bodies.mass[0], 100 * mass_before, 1e-9 * 100 * mass_before);
  // A step smaller than the natural one leaves the masses alone.
  World small = two_disk_world(0.1, 0.8);
  small.settings().density_scaling_dt_s = 0.5 * natural_dt;
  small.step();
  EXPECT_EQ(small.bodies.mass[0], mass_before);
  EXPECT_NEAR(small.dt_s(), natural_dt, 1e-12 * natural_dt);
}

TEST(TwoDisks, DirectStiffnessIsTheSameForEveryPairWhateverTheRadii) {
  // PFC's linear model (and LAMMPS's gran/hooke) set kn and ks themselves.
  WorldSettings settings;
  settings.damping = 0.0;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(
                        "linear", {{"kn_n_m", 3e8}, {"ks_n_m", 1e8}, {"friction", 0.5}}, "test")));
  world.bodies.add_disk(0.0, 0.0, 1e-3, 2650, 1.0, 0);
  world.bodies.add_disk(1.49e-3, 0.0, 0.5e-3, 2650, 1.0, 0);  // overlap 1e-5 m
  world.step();
  EXPECT_DOUBLE_EQ(world.pair_state(0, "kn_n_m"), 3e8);
  EXPECT_DOUBLE_EQ(world.pair_state(0, "ks_n_m"), 1e8);
  // The first step's force: kn x overlap, pushing the disks apart.
  EXPECT_NEAR(world.bodies.fx[1], 3e8 * 1e-5, 1e-6 * 3e8 * 1e-5);
  EXPECT_THROW(ContactModelRegistry::instance().create(
                   "linear", {{"kn_n_m", 3e8}, {"ks_n_m", 1e8}, {"modulus_pa", 1e9}, {"friction", 0.5}}, "test"),
               demcal::Error);
  EXPECT_THROW(ContactModelRegistry::instance().create("linear", {{"kn_n_m", 3e8}, {"friction", 0.5}}, "test"),
               demcal::Error);
  // A shear stiffness beside the modulus form was dropped without a word.
  EXPECT_THROW(ContactModelRegistry::instance().create(
                   "linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"ks_n_m", 1e8}, {"friction", 0.5}}, "test"),
               demcal::Error);
}
