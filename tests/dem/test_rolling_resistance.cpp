// A disk rolling on a plane under gravity stops where its rolling resistance
// says: a couple mu_r R F_n against the rotation decelerates a disk that rolls
// without slip at (2/3) mu_r g (I = m R^2 / 2), so from v0 it stops after
// 3 v0^2 / (4 mu_r g). Both types (rolling_resistance.hpp) reach it: type A
// (constant torque) at once, type C (spring-dashpot) once its spring is
// mobilised, after a rotation of a thousandth of a radian here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"

using namespace demcal::dem;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650, kThickness = 1e-3, kGravity = 9.81;
constexpr double kShearModulus = 3.5e7, kPoisson = 0.4;

// The disk rests on the floor at its static Hertz overlap and rolls at v0.
World rolling_disk(const nlohmann::json& rolling, double v0_m_s) {
  WorldSettings settings;
  settings.damping = 0;
  settings.thickness_m = kThickness;
  settings.gravity_y_m_s2 = -kGravity;
  World world(settings);
  nlohmann::json p = {{"shear_modulus_pa", kShearModulus}, {"poisson", kPoisson}, {"restitution", 0.5}, {"friction", 0.5}};
  p.update(rolling);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create("hertz_mindlin", p, "test")));
  const double mass = kDensity * M_PI * kRadius * kRadius * kThickness;
  const double e_eff = kShearModulus / (1 - kPoisson);  // same material both sides
  const double overlap = std::pow(3 * mass * kGravity / (4 * e_eff * std::sqrt(kRadius)), 2.0 / 3.0);
  world.bodies.add_disk(0.0, kRadius - overlap, kRadius, kDensity, kThickness, 0);
  world.bodies.vx[0] = v0_m_s;
  world.bodies.w[0] = -v0_m_s / kRadius;  // rolling to +x without slip
  Wall floor;
  floor.x0 = -1;
  floor.x1 = 1;
  floor.group = 1;
  world.walls.push_back(floor);
  return world;
}

double distance_after(World& world, double time_s) {
  while (world.time_s() < time_s) world.step();
  return world.bodies.x[0];
}

}  // namespace

TEST(RollingResistance, ConstantTorqueStopsTheDiskWhereTheClosedFormSays) {
  const double v0 = 0.05, mu_r = 0.05;
  const double stop_distance = 3 * v0 * v0 / (4 * mu_r * kGravity);
  const double stop_time = v0 / (2.0 / 3.0 * mu_r * kGravity);
  World world = rolling_disk({{"rolling_friction_cdt", mu_r}}, v0);
  EXPECT_NEAR(distance_after(world, 0.5 * stop_time), 0.75 * stop_distance, 0.01 * stop_distance);  // v falls linearly
  EXPECT_NEAR(distance_after(world, 1.5 * stop_time), stop_distance, 0.01 * stop_distance);
  EXPECT_LT(std::abs(world.bodies.vx[0]), 1e-3 * v0);
}

TEST(RollingResistance, SpringDashpotStopsTheDiskWhereTheClosedFormSays) {
  const double v0 = 0.05, mu_r = 0.05;
  const double stop_distance = 3 * v0 * v0 / (4 * mu_r * kGravity);
  const double stop_time = v0 / (2.0 / 3.0 * mu_r * kGravity);
  World world = rolling_disk({{"rolling_friction_epsd", mu_r}}, v0);
  EXPECT_NEAR(distance_after(world, 0.5 * stop_time), 0.75 * stop_distance, 0.01 * stop_distance);
  EXPECT_NEAR(distance_after(world, 2.0 * stop_time), stop_distance, 0.01 * stop_distance);
  EXPECT_LT(std::abs(world.bodies.vx[0]), 1e-3 * v0);
}

TEST(RollingResistance, WithoutItTheDiskRollsOn) {
  const double v0 = 0.05;
  World world = rolling_disk(nlohmann::json::object(), v0);
  EXPECT_NEAR(distance_after(world, 0.1), v0 * 0.1, 0.01 * v0 * 0.1);
}

namespace {

// Two equal disks pressed against each other between two walls (no gravity,
// no sliding friction, so nothing but rolling resistance couples the spins):
// disk 0 spins at w0, disk 1 is at rest.
World pressed_pair(const nlohmann::json& rolling, double w0) {
  WorldSettings settings;
  settings.damping = 0;
  settings.thickness_m = kThickness;
  World world(settings);
  nlohmann::json p = {{"shear_modulus_pa", kShearModulus}, {"poisson", kPoisson}, {"restitution", 0.5}, {"friction", 0.0}};
  p.update(rolling);
  const auto model = world.add_model(ContactModelRegistry::instance().create("hertz_mindlin", p, "test"));
  world.assign(0, 0, model);
  world.assign(0, 1, model);
  const double overlap = 1e-3 * kRadius;
  world.bodies.add_disk(kRadius - overlap, 0, kRadius, kDensity, kThickness, 0);
  world.bodies.add_disk(3 * kRadius - 2 * overlap, 0, kRadius, kDensity, kThickness, 0);
  world.bodies.fixed[0] = world.bodies.fixed[1] = 0;
  Wall left, right;
  left.x0 = left.x1 = 0;
  left.y0 = -2 * kRadius;
  left.y1 = 2 * kRadius;
  left.inward_nx = 1;
  right = left;
  right.x0 = right.x1 = 4 * kRadius - 3 * overlap;
  right.inward_nx = -1;
  left.group = right.group = 1;
  world.walls = {left, right};
  world.bodies.w[0] = w0;
  return world;
}

}  // namespace

// Type A acts on each disk's own spin (EDEM's form): the spinning disk slows
// at a constant rate and stops for good; the disk at rest next to it stays
// exactly at rest. LIGGGHTS' relative form (kept as
// rolling_friction_cdt_relative) drags the resting disk along instead.
TEST(RollingResistance, TypeAActsOnEachDisksOwnSpinDiskAgainstDisk) {
  const double w0 = 400.0, mu_r = 0.05;
  World world = pressed_pair({{"rolling_friction_cdt", mu_r}}, w0);
  std::vector<double> spin;
  for (int k = 0; k < 4; ++k) {
    world.run(100);
    spin.push_back(world.bodies.w[0]);
    ASSERT_EQ(world.bodies.w[1], 0.0) << "the resting disk was turned";
  }
  // A constant couple: equal drops in equal times while it spins.
  ASSERT_GT(spin[3], 0.0) << "dt " << world.dt_s() << ", spins " << spin[0] << " " << spin[1] << " " << spin[2];
  EXPECT_NEAR(spin[0] - spin[1], spin[2] - spin[3], 1e-6 * w0);
  EXPECT_GT(spin[0] - spin[1], 0.0);
  const double rate = (spin[0] - spin[1]) / (100 * world.dt_s());
  world.run(static_cast<std::uint64_t>(2 * spin[3] / rate / world.dt_s()) + 10);
  EXPECT_EQ(world.bodies.w[0], 0.0) << "stopped, it stays stopped";
  world.run(1000);
  EXPECT_EQ(world.bodies.w[0], 0.0);

  // The resting disk's spin under the relative form swings about as the pair's contacts ring (its sign too):
  // the largest it reaches over the same 400 steps.
  World relative = pressed_pair({{"rolling_friction_cdt_relative", mu_r}}, w0);
  double most = 0;
  for (int k = 0; k < 400; ++k) {
    relative.step();
    most = std::max(most, std::abs(relative.bodies.w[1]));
  }
  EXPECT_GT(most, 1e-4 * w0) << "the relative form drags the resting disk along";
}

// Static resistance: on a slope of tan(theta) = mu_r / 2 a disk held by type
// A rolling friction stays where it was put; with the relative form's ramp
// below its threshold it creeps down.
TEST(RollingResistance, TypeAHoldsADiskStillOnASlopeTheRelativeFormLetsItCreep) {
  const double mu_r = 0.05, theta = std::atan(0.5 * mu_r);
  // How far the disk moves over steps 10,000 to 20,000, after it has settled on the slope's springs.
  auto creep = [&](const nlohmann::json& rolling) {
    World world = rolling_disk(rolling, 0.0);
    world.settings().gravity_x_m_s2 = kGravity * std::sin(theta);
    world.settings().gravity_y_m_s2 = -kGravity * std::cos(theta);
    world.run(10000);
    const double x0 = world.bodies.x[0];
    world.run(10000);
    return std::abs(world.bodies.x[0] - x0);
  };
  EXPECT_LT(creep({{"rolling_friction_cdt", mu_r}}), 1e-9 * kRadius);
  EXPECT_GT(creep({{"rolling_friction_cdt_relative", mu_r}}), 1e-3 * kRadius);
}
