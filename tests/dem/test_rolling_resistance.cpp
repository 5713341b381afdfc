// A disk rolling on a plane under gravity stops where its rolling resistance
// says: a couple mu_r R F_n against the rotation decelerates a disk that rolls
// without slip at (2/3) mu_r g (I = m R^2 / 2), so from v0 it stops after
// 3 v0^2 / (4 mu_r g). Both types (rolling_resistance.hpp) reach it: type A
// (constant torque) at once, type C (spring-dashpot) once its spring is
// mobilised, after a rotation of a thousandth of a radian here.
#include <gtest/gtest.h>

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
