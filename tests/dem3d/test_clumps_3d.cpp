// 3D clumps against closed forms: a two-sphere clump's mass and inertia, a
// free symmetric top's torque-free precession (Euler's equations: the spin
// turns about the symmetry axis in the body frame at (I3 - I1) / I1 w3, the
// angular momentum and the energy stay), a clump that falls onto a plane and
// comes to rest on both spheres, and the same bits on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650;

// Two spheres 1.3 radii apart along `axis` (He et al.'s aspect ratio 1.3 has
// them 0.6 r apart; here apart enough that a symmetric top has I3 != I1).
World two_sphere_clump_world(Vec3 centre, Vec3 axis, double gap_radii) {
  WorldSettings settings;
  settings.damping = 0;
  World world(settings);
  const Vec3 half = (0.5 * gap_radii * kRadius / norm(axis)) * axis;
  world.spheres.add_sphere(centre - half, kRadius, kDensity, 0);
  world.spheres.add_sphere(centre + half, kRadius, kDensity, 0);
  const ClumpShape shape = clump_of_spheres({centre - half, centre + half}, {kRadius, kRadius}, kDensity);
  world.add_clump({0, 1}, shape.mass_kg, shape.principal_inertia_kg_m2, shape.orientation, shape.centre_m);
  return world;
}

}  // namespace

TEST(Clumps3D, TwoSpheresWeighAndTurnAsTheirSum) {
  const double d = 1.3 * kRadius;
  const ClumpShape s = clump_of_spheres({{0, 0, -0.5 * d}, {0, 0, 0.5 * d}}, {kRadius, kRadius}, kDensity);
  const double m = kDensity * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius;
  EXPECT_NEAR(s.mass_kg, 2 * m, 1e-12 * m);
  EXPECT_NEAR(norm(s.centre_m), 0.0, 1e-15);
  // About the axis: 2 (2/5 m r^2); across it: that plus 2 m (d/2)^2. Sorted: the axis's is the smallest.
  const double axial = 0.8 * m * kRadius * kRadius, across = axial + 0.5 * m * d * d;
  EXPECT_NEAR(s.principal_inertia_kg_m2.x, axial, 1e-9 * across);
  EXPECT_NEAR(s.principal_inertia_kg_m2.y, across, 1e-9 * across);
  EXPECT_NEAR(s.principal_inertia_kg_m2.z, across, 1e-9 * across);
  // The first principal axis is the clump's axis.
  EXPECT_NEAR(std::abs(to_world(s.orientation, {1, 0, 0}).z), 1.0, 1e-12);
}

TEST(Clumps3D, AFreeSymmetricTopPrecessesAsEulerSays) {
  World world = two_sphere_clump_world({0, 0, 0}, {1, 1, 0}, 1.3);
  Clump& c = world.clumps()[0];
  const Vec3 inertia = c.principal_inertia_kg_m2;  // x: the symmetry axis (I3), y = z (I1)
  // Spin mostly about the symmetry axis, a little across it (body frame).
  const Vec3 spin_body = {100.0, 10.0, 0.0};
  c.angular_momentum = to_world(c.orientation, {inertia.x * spin_body.x, inertia.y * spin_body.y, 0});
  const Vec3 momentum = c.angular_momentum;
  const double energy = c.kinetic_energy();
  const double rate = (inertia.x - inertia.y) / inertia.y * spin_body.x;  // the body-frame precession rate
  world.settings().fixed_dt_s = 1e-6;  // no contacts to set a step
  world.refresh();
  const double period = 2 * M_PI / std::abs(rate), dt = world.dt_s();
  const auto steps = static_cast<std::uint64_t>(std::round(0.25 * period / dt));
  world.run(steps);
  const double t = world.time_s();
  const Vec3 now = to_body(c.orientation, c.spin());
  // w_across(t) = 10 (cos, -sin) of (rate t) in the body's y-z plane; w along the axis constant.
  EXPECT_NEAR(now.x, spin_body.x, 1e-6 * spin_body.x);
  EXPECT_NEAR(now.y, 10.0 * std::cos(rate * t), 1e-3 * 10.0);
  EXPECT_NEAR(now.z, 10.0 * std::sin(rate * t), 1e-3 * 10.0);
  EXPECT_EQ(c.angular_momentum.x, momentum.x);  // no torque: exactly kept
  EXPECT_NEAR(c.kinetic_energy(), energy, 1e-6 * energy);
  EXPECT_GT(steps, 100u);
}

TEST(Clumps3D, AClumpFallsOntoAPlaneAndRestsOnBothSpheres) {
  World world = two_sphere_clump_world({0, 0, 3 * kRadius}, {1, 0, 0.2}, 1.3);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e8}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  WorldSettings& settings = world.settings();
  settings.gravity_m_s2 = {0, 0, -9.81};
  settings.damping = 0.7;
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  world.run(60000);
  const Clump& c = world.clumps()[0];
  EXPECT_LT(norm(c.velocity_m_s), 1e-6);
  // Both spheres touch the plane: the clump lies flat, its weight shared.
  EXPECT_NEAR(world.spheres.z[0], world.spheres.z[1], 1e-7);
  EXPECT_NEAR(world.walls[0].force_n.z, -c.mass_kg * 9.81, 1e-4 * c.mass_kg * 9.81);
  EXPECT_EQ(world.pairs().size(), 0u);  // no pair inside the clump
}

TEST(Clumps3D, ClumpsAreRefusedWhenTheyCannotBe) {
  World world = two_sphere_clump_world({0, 0, 0}, {1, 0, 0}, 1.3);
  EXPECT_THROW(world.add_clump({0}, 1, {1, 1, 1}, {}, {}), demcal::Error);  // already in one
  world.spheres.add_sphere({0.01, 0, 0}, kRadius, kDensity, 0);
  EXPECT_THROW(world.add_clump({2}, 0, {1, 1, 1}, {}, {}), demcal::Error);
  EXPECT_THROW(world.add_clump({}, 1, {1, 1, 1}, {}, {}), demcal::Error);
}

// Density scaling raises the masses and inertias of spheres and clumps (never
// lowers them) until the step is the one asked; a restitution-damped model refuses it.
TEST(Clumps3D, DensityScalingReachesTheAskedStepWithClumps) {
  World world = two_sphere_clump_world({0, 0, 1.2 * kRadius}, {1, 0, 0}, 1.3);
  world.spheres.add_sphere({0.01, 0, 1.001 * kRadius}, kRadius, kDensity, 0);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e9}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  world.refresh();
  const double unscaled = world.dt_s(), clump_mass = world.clumps()[0].mass_kg, sphere_mass = world.spheres.mass[2];
  world.settings().density_scaling_dt_s = 10 * unscaled;
  world.refresh();
  EXPECT_NEAR(world.dt_s(), 10 * unscaled, 1e-9 * unscaled);
  EXPECT_GT(world.clumps()[0].mass_kg, 10 * clump_mass);
  EXPECT_GT(world.spheres.mass[world.index_of(2)], 10 * sphere_mass);
  world.run(1000);  // and it runs stably at that step
  EXPECT_TRUE(std::isfinite(world.spheres.z[0]));

  World hertz = two_sphere_clump_world({0, 0, 0}, {1, 0, 0}, 1.3);
  hertz.assign(0, 1, hertz.add_model(ContactModelRegistry::instance().create(
                         "hertz_mindlin", {{"shear_modulus_pa", 1e8}, {"poisson", 0.25}, {"restitution", 0.5}, {"friction", 0.5}},
                         "test")));
  hertz.settings().density_scaling_dt_s = 1e-4;
  EXPECT_THROW(hertz.refresh(), demcal::Error);
}

// Enough clumps that their integration splits over threads: layers of them settling on a plane and on each other
// give the same bits on one thread and on two.
TEST(Clumps3D, ManyClumpsGiveTheSameBitsOnOneAndTwoThreads) {
  auto settle = [](int threads) {
    WorldSettings settings;
    settings.threads = threads;
    settings.min_spheres_per_thread = 1;
    settings.damping = 0.1;
    settings.gravity_m_s2 = {0, 0, -9.81};
    World world(settings);
    const int side = 8, layers = 6;  // 384 clumps, 768 spheres
    const double pitch = 3.4 * kRadius;
    for (int l = 0; l < layers; ++l)
      for (int a = 0; a < side; ++a)
        for (int b = 0; b < side; ++b) {
          // Lying clumps, each layer just touching the one below and shifted against it, the first on the plane.
          const Vec3 centre = {a * pitch + 0.4 * kRadius * (l % 2), b * pitch, (1 + 2 * l) * kRadius};
          const Vec3 axis = {1.0, 0.15 * ((a + b + l) % 5), 0.0};
          const Vec3 half = (0.65 * kRadius / norm(axis)) * axis;
          const std::size_t first = world.spheres.size();
          world.spheres.add_sphere(centre - half, kRadius, kDensity, 0);
          world.spheres.add_sphere(centre + half, kRadius, kDensity, 0);
          const ClumpShape shape = clump_of_spheres({centre - half, centre + half}, {kRadius, kRadius}, kDensity);
          world.add_clump({first, first + 1}, shape.mass_kg, shape.principal_inertia_kg_m2, shape.orientation,
                          shape.centre_m);
        }
    world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                           "linear", {{"modulus_pa", 1e8}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
    world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
    world.run(1500);
    EXPECT_EQ(world.threads_in_use(), threads);
    return world;
  };
  const World one = settle(1), two = settle(2);
  ASSERT_EQ(one.clumps().size(), 384u);
  ASSERT_EQ(one.spheres.size(), two.spheres.size());
  for (std::size_t i = 0; i < one.spheres.size(); ++i) {
    ASSERT_EQ(std::memcmp(&one.spheres.z[i], &two.spheres.z[i], sizeof(double)), 0) << i;
    ASSERT_EQ(std::memcmp(&one.spheres.vx[i], &two.spheres.vx[i], sizeof(double)), 0) << i;
  }
  EXPECT_LT(one.walls[0].force_n.z, 0.0);  // the layers press on the plane: contacts, not free flight, were compared
}
