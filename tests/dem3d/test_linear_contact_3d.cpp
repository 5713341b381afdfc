// The 3D linear contact against closed forms: PFC3D's stiffness from the
// modulus, a head-on collision that lasts pi sqrt(m_eff / kn) and returns
// every joule without damping, a sphere resting on a plane at overlap
// m g / kn, and a contact force that a rigid rotation of the pair does not
// change (it turns with the pair).
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;
namespace dem = demcal::dem;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650, kModulus = 1e9;

std::unique_ptr<ContactModel> linear(double friction = 0.5) {
  return ContactModelRegistry::instance().create(
      "linear", {{"modulus_pa", kModulus}, {"kn_ks", 2.0}, {"friction", friction}}, "test");
}

World two_spheres(double speed_m_s, Vec3 direction, double safety) {
  WorldSettings settings;
  settings.damping = 0.0;
  settings.safety_factor = safety;
  World world(settings);
  world.assign(0, 0, world.add_model(linear()));
  const Vec3 d = (1.0 / norm(direction)) * direction;
  world.spheres.add_sphere({}, kRadius, kDensity, 0);
  world.spheres.add_sphere(2.05 * kRadius * d, kRadius, kDensity, 0);
  world.spheres.set_velocity(0, (0.5 * speed_m_s) * d);
  world.spheres.set_velocity(1, (-0.5 * speed_m_s) * d);
  return world;
}

// Rotates v about the unit axis u by angle a (Rodrigues).
Vec3 rotate(Vec3 v, Vec3 u, double a) {
  return std::cos(a) * v + std::sin(a) * cross(u, v) + ((1 - std::cos(a)) * dot(u, v)) * u;
}

}  // namespace

TEST(LinearContact3D, StiffnessIsPfc3dDeformability) {
  World world = two_spheres(0.1, {1, 0, 0}, 0.8);
  world.refresh();
  ASSERT_EQ(world.pairs().size(), 1u);
  // kn = pi r^2 E / (R1 + R2), r = min R: pi R E / 2 for equal spheres.
  EXPECT_NEAR(world.pair_state(0, "kn_n_m"), M_PI * kRadius * kModulus / 2, 1e-9 * kModulus * kRadius);
  EXPECT_NEAR(world.pair_state(0, "ks_n_m"), M_PI * kRadius * kModulus / 4, 1e-9 * kModulus * kRadius);
}

TEST(LinearContact3D, HeadOnCollisionLastsHalfAPeriodAndKeepsTheEnergy) {
  for (const Vec3 direction : {Vec3{1, 0, 0}, Vec3{1, -2, 3}}) {
    World world = two_spheres(0.2, direction, 0.02);
    const double before = world.kinetic_energy();
    double touching_s = 0, step_s = 0;
    for (int s = 0; s < 200000 && (touching_s == 0 || world.touching_pairs() > 0); ++s) {
      world.step();
      if (world.touching_pairs() > 0) touching_s += world.dt_s(), step_s = world.dt_s();
    }
    const double kn = M_PI * kRadius * kModulus / 2;
    const double m = kDensity * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius;
    const double expected_s = M_PI * std::sqrt(0.5 * m / kn);
    // Detected to within a step at each end, and the check tight (2 %).
    EXPECT_NEAR(touching_s, expected_s, 2 * step_s);
    EXPECT_LT(2 * step_s, 0.02 * expected_s);
    // Every joule back (no damping, central differences), the velocities reversed along the line.
    EXPECT_NEAR(world.kinetic_energy(), before, 1e-4 * before);
    const Vec3 d = (1.0 / norm(direction)) * direction;
    EXPECT_NEAR(dot(world.spheres.velocity(0), d), -0.1, 1e-4 * 0.1);
    // Head on: no spin, and the spheres leave along the line they came.
    EXPECT_NEAR(norm(world.spheres.spin(0)), 0.0, 1e-12);
  }
}

TEST(LinearContact3D, ASphereRestsOnAPlaneAtTheStaticOverlap) {
  WorldSettings settings;
  settings.gravity_m_s2 = {0, 0, -9.81};
  settings.damping = 0.7;
  World world(settings);
  world.assign(0, 1, world.add_model(linear()));
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}, 1));
  world.spheres.add_sphere({0, 0, kRadius * 1.001}, kRadius, kDensity, 0);
  world.run(40000);
  const double m = world.spheres.mass[0];
  // A sphere on a wall: r = L = R, so kn = pi R E.
  const double kn = M_PI * kRadius * kModulus;
  EXPECT_NEAR(kRadius - world.spheres.z[0], m * 9.81 / kn, 1e-6 * m * 9.81 / kn);
  EXPECT_NEAR(world.walls[0].force_n.z, -m * 9.81, 1e-6 * m * 9.81);
}

// A pair turned rigidly (positions on a circle, velocities omega x r, spins
// omega): the normal force keeps its size and the shear force turns with the
// pair, for an axis across the contact and one along it (twist).
TEST(LinearContact3D, ARigidRotationTurnsTheForceWithThePair) {
  auto model = linear(10.0);  // no sliding
  dem::ContactSet set;
  set.set_layout({model->state_columns().size()});
  set.assign_blocks({1});
  set.i[0] = 0, set.j[0] = 1;
  for (const Vec3 axis_raw : {Vec3{0, 0, 1}, Vec3{1, 0, 0}, Vec3{1, 2, 3}}) {
    const Vec3 axis = (1.0 / norm(axis_raw)) * axis_raw;
    Spheres s;
    const Vec3 x0 = {-0.99 * kRadius, 0, 0}, x1 = {0.99 * kRadius, 0, 0};
    s.add_sphere(x0, kRadius, kDensity, 0);
    s.add_sphere(x1, kRadius, kDensity, 0);
    dem::PairBlock block = set.block(0);
    for (std::size_t c = 0; c < model->state_columns().size(); ++c) block.column[c][0] = 0;
    PairInfo info;
    info.radius_i = info.radius_j = kRadius;
    model->initialise(block, 0, info);
    std::vector<double> f(9);  // the force on i, then the moments of i and j per component
    const PairForces out{&f[0], &f[1], &f[2], &f[3], &f[5], &f[7]};
    // First a shear: sphere 1 slides along y for 100 steps of 1e-7 s at 1 mm/s.
    const double dt = 1e-7;
    s.set_velocity(1, {0, 1e-3, 0});
    for (int k = 0; k < 100; ++k) model->sphere_forces(block, s, out, {dt, 0});
    s.set_velocity(1, {});
    model->sphere_forces(block, s, out, {dt, 0});
    const Vec3 force0 = {f[0], f[1], f[2]};
    ASSERT_GT(std::abs(force0.y), 0.0);
    // Then a quarter turn in 20,000 steps at 1 rad per 0.1 ms.
    const double omega = 1e4, steps = 20000, angle_step = omega * dt;
    for (int k = 1; k <= steps; ++k) {
      const double a = angle_step * k;
      const Vec3 p0 = rotate(x0, axis, a), p1 = rotate(x1, axis, a);
      s.x = {p0.x, p1.x}, s.y = {p0.y, p1.y}, s.z = {p0.z, p1.z};
      s.set_velocity(0, cross(omega * axis, p0));
      s.set_velocity(1, cross(omega * axis, p1));
      s.set_spin(0, omega * axis);
      s.set_spin(1, omega * axis);
      model->sphere_forces(block, s, out, {dt, 0});
    }
    const Vec3 expected = rotate(force0, axis, angle_step * steps);
    const Vec3 force = {f[0], f[1], f[2]};
    // The update is first order in the step's angle (1e-3 rad here): 1e-5 of the force over a quarter turn.
    EXPECT_LT(norm(force - expected), 1e-5 * norm(force0)) << "axis " << axis.x << " " << axis.y << " " << axis.z;
  }
}
