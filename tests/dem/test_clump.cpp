// Rigid clumps: pairs inside a clump never interact, a free clump keeps its
// shape and spin, and a clump bounces off a wall as one rigid body.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/equilibrium.hpp"
#include "demcal/dem/world.hpp"

using namespace demcal::dem;

namespace {

World world_with_linear(double safety) {
  WorldSettings settings;
  settings.damping = 0;
  settings.safety_factor = safety;
  World world(settings);
  auto model = [] {
    return ContactModelRegistry::instance().create("linear", {{"modulus_pa", 1e9}, {"kn_ks", 1.0}, {"friction", 0.0}},
                                                   "test");
  };
  world.assign(0, 0, world.add_model(model()));
  world.assign(0, 1, world.add_model(model()));
  return world;
}

// Three overlapping disks of radius 1 mm in a row, a clump of mass m and inertia I.
std::size_t add_rod(World& world, double x, double y, double m, double inertia) {
  std::vector<std::size_t> members;
  for (int k = -1; k <= 1; ++k) members.push_back(world.bodies.add_disk(x + k * 1.5e-3, y, 1e-3, 2650, 1, 0));
  return world.add_clump(members, m, inertia, x, y);
}

double member_distance(const World& world, std::size_t a, std::size_t b) {
  return std::hypot(world.bodies.x[a] - world.bodies.x[b], world.bodies.y[a] - world.bodies.y[b]);
}

}  // namespace

TEST(Clump, PairsInsideAClumpAreNeverContacts) {
  World world = world_with_linear(0.5);
  add_rod(world, 0, 0, 0.05, 1e-7);
  world.bodies.add_disk(0, 2.05e-3, 1e-3, 2650, 1, 0);  // a free disk just above the middle member
  world.refresh();
  for (std::size_t k = 0; k < world.pairs().size(); ++k) {
    const int ci = world.bodies.clump[world.pairs().i[k]], cj = world.bodies.clump[world.pairs().j[k]];
    EXPECT_FALSE(ci >= 0 && ci == cj);
  }
  EXPECT_GE(world.pairs().size(), 1u);  // the free disk's pairs are there
  world.run(100);                       // overlapping members push nothing apart
  EXPECT_NEAR(member_distance(world, 0, 1), 1.5e-3, 1e-15);
}

TEST(Clump, AFreeClumpKeepsItsShapeSpinAndMomentum) {
  World world = world_with_linear(0.5);
  add_rod(world, 0, 0, 0.05, 1e-7);
  Clump& c = world.clumps()[0];
  c.vx = 0.01;
  c.w = 20.0;
  world.run(2000);
  const Clump& after = world.clumps()[0];
  EXPECT_DOUBLE_EQ(after.w, 20.0);
  EXPECT_DOUBLE_EQ(after.vx, 0.01);
  EXPECT_NEAR(after.x, 0.01 * world.time_s(), 1e-15);
  EXPECT_NEAR(member_distance(world, 0, 2), 3e-3, 1e-12 * 3e-3);
  // The members turned with the clump: the rod's angle is w t.
  const double angle = std::atan2(world.bodies.y[2] - world.bodies.y[0], world.bodies.x[2] - world.bodies.x[0]);
  EXPECT_NEAR(std::remainder(angle - 20.0 * world.time_s(), 2 * M_PI), 0.0, 1e-9);
}

TEST(Clump, BouncesOffAWallAsOneRigidBody) {
  World world = world_with_linear(0.05);
  const double m = 0.05, inertia = 1e-7;
  add_rod(world, 0, 1.05e-3, m, inertia);
  world.clumps()[0].vy = -0.1;
  Wall floor;
  floor.x0 = -1;
  floor.x1 = 1;
  floor.group = 1;
  world.walls.push_back(floor);
  const double energy = world.kinetic_energy();
  for (int s = 0; s < 200000 && world.clumps()[0].vy < 0.0999; ++s) world.step();
  // Three members touch the floor alike: a straight bounce, no spin, energy kept.
  EXPECT_NEAR(world.clumps()[0].vy, 0.1, 1e-4);
  EXPECT_NEAR(world.clumps()[0].w, 0.0, 1e-9);
  EXPECT_NEAR(world.kinetic_energy(), energy, 1e-3 * energy);
  EXPECT_NEAR(member_distance(world, 0, 2), 3e-3, 1e-12 * 3e-3);
}

TEST(Clump, AnOffCentreImpactSetsItSpinning) {
  World world = world_with_linear(0.05);
  add_rod(world, 0, 2e-3, 0.05, 1e-7);
  world.clumps()[0].vy = -0.1;
  Wall floor;  // only the left end reaches this short floor
  floor.x0 = -3e-3;
  floor.x1 = -1.2e-3;
  floor.y0 = floor.y1 = 0.95e-3;
  floor.group = 1;
  world.walls.push_back(floor);
  for (int s = 0; s < 200000 && world.clumps()[0].w == 0.0; ++s) world.step();
  world.run(2000);
  // An upward push left of the centre turns the rod clockwise (w < 0).
  EXPECT_LT(world.clumps()[0].w, 0.0);
  EXPECT_NEAR(member_distance(world, 0, 2), 3e-3, 1e-12 * 3e-3);
}

TEST(Clump, TheForceRatioCountsAClumpAsOneBody) {
  // A rod (three disks from -1.5 to +1.5 mm) squeezed between two fixed
  // disks that overlap its ends equally: its members carry +F and -F, the rod
  // as a whole nothing. Free bodies: the two outer disks (|F| each) and the
  // rod (0), so PFC's ratio is (2F / 3) / F; counting members alone it never
  // falls, and a clumped specimen never reaches equilibrium.
  World world = world_with_linear(0.8);
  add_rod(world, 0, 0, 1e-3, 1e-9);
  const double overlap = 1e-5;
  for (double side : {-1.0, 1.0}) {
    const std::size_t d = world.bodies.add_disk(side * (3.5e-3 - overlap), 0, 1e-3, 2650, 1, 0);
    world.bodies.fixed[d] = 1;
  }
  world.step();
  EXPECT_NEAR(force_ratio(world), 2.0 / 3.0, 1e-9);
}

TEST(Clump, BadClumpsAreRejected) {
  World world = world_with_linear(0.5);
  add_rod(world, 0, 0, 0.05, 1e-7);
  EXPECT_THROW(world.add_clump({0}, 1.0, 1.0, 0, 0), demcal::Error);    // already in a clump
  EXPECT_THROW(world.add_clump({99}, 1.0, 1.0, 0, 0), demcal::Error);   // no such disk
  std::size_t free_disk = world.bodies.add_disk(1, 1, 1e-3, 2650, 1, 0);
  EXPECT_THROW(world.add_clump({free_disk}, 0.0, 1.0, 1, 1), demcal::Error);
}

TEST(Clump, DensityScalingReachesTheRequestedStepWithClumps) {
  // Natural step of a 1 mm disk on a 1 GPa contact: about 1e-7 s; ask for 100 times that.
  const double requested_dt_s = 1e-5;
  WorldSettings settings;
  settings.density_scaling_dt_s = requested_dt_s;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(
                        "linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.5}, {"friction", 0.5}}, "test")));
  add_rod(world, 0, 0, 1e-3, 1e-10);
  world.bodies.add_disk(3.4e-3, 0, 1e-3, 2650, 1, 0);   // touching the rod's right member
  world.bodies.add_disk(0, 1.95e-3, 1e-3, 2650, 1, 0);  // touching its middle member
  world.refresh();
  EXPECT_NEAR(world.dt_s(), requested_dt_s, 1e-12 * requested_dt_s);
  const Clump& rod = world.clumps()[0];
  EXPECT_GT(rod.mass, 1e-3);  // raised: the clump, not its members, is what moves
  EXPECT_GT(rod.inertia, 1e-10);
}

TEST(Clump, DensityScalingRefusesGravity) {
  WorldSettings settings;
  settings.density_scaling_dt_s = 1e-5;
  settings.gravity_y_m_s2 = -9.81;
  EXPECT_THROW(World{settings}, demcal::Error);
}
