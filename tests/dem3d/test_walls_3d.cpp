// The 3D walls against closed forms: a sphere resting in a horizontal
// cylinder at the static overlap m g / kn, a sphere in a drum turning about
// its axis that ends rolling without slip (spin = drum rate x drum radius /
// sphere radius, centre at rest at the bottom), a turning plane's axis, and
// the walls' own checks.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/vtk_writer.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650;

World drum_world(double modulus_pa, double drum_radius_m) {
  WorldSettings settings;
  settings.gravity_m_s2 = {0, 0, -9.81};
  World world(settings);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", modulus_pa}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  // A drum along x through the origin, 10 mm long, spheres inside.
  world.walls.push_back(make_cylinder({-0.005, 0, 0}, {1, 0, 0}, drum_radius_m, 0.01));
  world.spheres.add_sphere({0, 0, -drum_radius_m + kRadius * 1.001}, kRadius, kDensity, 0);
  return world;
}

}  // namespace

TEST(Walls3D, ASphereRestsInACylinderAtTheStaticOverlap) {
  World world = drum_world(1e9, 0.02);
  world.run(40000);
  const double m = world.spheres.mass[0], kn = M_PI * kRadius * 1e9;
  const double overlap = kRadius - (0.02 - std::hypot(world.spheres.y[0], world.spheres.z[0]));
  EXPECT_NEAR(overlap, m * 9.81 / kn, 1e-6 * m * 9.81 / kn);
  EXPECT_NEAR(world.walls[0].force_n.z, -m * 9.81, 1e-6 * m * 9.81);
  EXPECT_NEAR(world.spheres.y[0], 0.0, 1e-12);
}

TEST(Walls3D, ASphereInATurningDrumRollsWithoutSlip) {
  const double drum_radius = 0.02, drum_rate = 1.0;
  World world = drum_world(1e7, drum_radius);
  world.walls[0].spin_rad_s = {drum_rate, 0, 0};
  while (world.time_s() < 3.0) world.step();
  const Vec3 spin = world.spheres.spin(0);
  // The contact point moves with the drum's surface: w r = drum rate x drum radius (distance from axis to contact).
  EXPECT_NEAR(spin.x, drum_rate * drum_radius / kRadius, 1e-3 * drum_rate * drum_radius / kRadius);
  EXPECT_NEAR(spin.y, 0.0, 1e-6);
  EXPECT_NEAR(norm(world.spheres.velocity(0)), 0.0, 1e-6);
  EXPECT_NEAR(world.spheres.y[0], 0.0, 1e-5 * drum_radius);  // back at the bottom (its rolling sway decays slowly)
  // The drum feels the sphere's weight and no torque about its axis once it rolls.
  EXPECT_NEAR(world.walls[0].moment_nm.x, 0.0, 1e-6 * world.spheres.mass[0] * 9.81 * drum_radius);
}

TEST(Walls3D, ATurningPlaneTurnsItsNormal) {
  World world;
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  world.walls[0].spin_rad_s = {0, M_PI / 2, 0};  // a quarter turn in a second about y
  world.spheres.add_sphere({0, 0, 0.5}, kRadius, kDensity, 0);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e6}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  world.refresh();
  while (world.time_s() < 1.0 - 0.5 * world.dt_s()) world.step();
  EXPECT_NEAR(world.walls[0].axis.x, std::sin(M_PI / 2 * world.time_s()), 1e-9);
  EXPECT_NEAR(norm(world.walls[0].axis), 1.0, 1e-12);
}

TEST(Walls3D, BadWallsAreRefused) {
  EXPECT_THROW(make_cylinder({0, 0, 0}, {0, 0, 1}, 0.0, 0.1), demcal::Error);
  EXPECT_THROW(make_cylinder({0, 0, 0}, {0, 0, 1}, -1.0, 0.1), demcal::Error);
  EXPECT_THROW(make_cylinder({0, 0, 0}, {0, 0, 0}, 1.0, 0.1), demcal::Error);
  EXPECT_THROW(make_plane({0, 0, 0}, {0, 0, 0}), demcal::Error);
  try {
    make_cylinder({0, 0, 0}, {0, 0, 1}, 0.0, 0.1);
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("radius_m > 0"), std::string::npos) << e.what();
  }
}

// A snapshot ParaView reads: every sphere a point with its radius, every wall facets.
TEST(Walls3D, VtkSnapshotsHoldEverySphereAndWall) {
  World world = drum_world(1e7, 0.02);
  world.walls.push_back(make_plane({0, 0, -0.03}, {0, 0, 1}));
  world.spheres.add_sphere({0.001, 0, 0}, 2e-3, kDensity, 0);
  world.refresh();
  const std::string spheres_path = ::testing::TempDir() + "spheres.vtk", walls_path = ::testing::TempDir() + "walls.vtk";
  write_vtk_spheres(world, spheres_path);
  write_vtk_walls(world, walls_path);
  std::ifstream spheres(spheres_path), walls(walls_path);
  std::stringstream a, b;
  a << spheres.rdbuf();
  b << walls.rdbuf();
  EXPECT_NE(a.str().find("POINTS 2 double"), std::string::npos);
  EXPECT_NE(a.str().find("SCALARS radius double 1\nLOOKUP_TABLE default\n"), std::string::npos);
  EXPECT_NE(a.str().find("0.002\n"), std::string::npos);
  // 32 facets of the drum and one patch of the floor.
  EXPECT_NE(b.str().find("POLYGONS 33 "), std::string::npos);
  EXPECT_NE(b.str().find("POINTS 68 double"), std::string::npos);
  // A mesh's triangle is drawn as its three corners.
  world.walls = {make_triangle({0, 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}, 0, {})};
  write_vtk_walls(world, walls_path);
  std::ifstream triangle(walls_path);
  std::stringstream c;
  c << triangle.rdbuf();
  EXPECT_NE(c.str().find("POINTS 3 double"), std::string::npos);
  EXPECT_NE(c.str().find("POLYGONS 1 4\n3 0 1 2\n"), std::string::npos);
}

// Servo walls: a plane pressing a column of spheres onto a floor, and a
// cylinder confining a packing, each bring the stress they feel to the target.
TEST(Walls3D, ServoWallsHoldTheirStress) {
  WorldSettings settings;
  World world(settings);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e9}, {"kn_ks", 1.5}, {"friction", 0.3}}, "test")));
  world.assign(0, 0, 0);
  for (int k = 0; k < 3; ++k) world.spheres.add_sphere({0, 0, kRadius * (1 + 2 * k)}, kRadius, kDensity, 0);
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  world.walls.push_back(make_plane({0, 0, 6.2 * kRadius}, {0, 0, -1}));  // a gap: the servo closes it
  Wall& top = world.walls[1];
  top.servo = true;
  top.servo_area_m2 = 4 * kRadius * kRadius;  // a square column of side 2R
  top.servo_target_stress_pa = 1e5;
  top.servo_max_speed_m_s = 0.05;
  world.run(40000);
  EXPECT_NEAR(world.walls[1].normal_force_n / world.walls[1].servo_area_m2, 1e5, 1e-3 * 1e5);
  EXPECT_NEAR(-world.walls[0].force_n.z, 1e5 * 4 * kRadius * kRadius, 1e-3 * 0.4);

  // A cylinder of radius 6 R round a packing of 19 spheres in a layer, squeezed to 2e5 Pa on its 2 R height.
  World ring(settings);
  ring.assign(0, 1, ring.add_model(ContactModelRegistry::instance().create(
                        "linear", {{"modulus_pa", 1e9}, {"kn_ks", 1.5}, {"friction", 0.0}}, "test")));
  ring.assign(0, 0, 0);
  for (int a = -2; a <= 2; ++a)
    for (int b = -2; b <= 2; ++b)
      if (std::abs(a + b) <= 2) ring.spheres.add_sphere({2.1 * kRadius * (a + 0.5 * b), 2.1 * kRadius * 0.866 * b, kRadius},
                                                        kRadius, kDensity, 0);
  ring.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  ring.walls.push_back(make_plane({0, 0, 2 * kRadius}, {0, 0, -1}));
  ring.walls.push_back(make_cylinder({0, 0, 0}, {0, 0, 1}, 6 * kRadius, 2 * kRadius));
  Wall& cylinder = ring.walls[2];
  cylinder.servo = true;
  cylinder.servo_target_stress_pa = 2e5;
  cylinder.servo_max_speed_m_s = 0.05;
  ring.run(60000);
  EXPECT_NEAR(ring.walls[2].normal_force_n / ring.walls[2].loaded_area_m2(), 2e5, 1e-2 * 2e5);
  EXPECT_LT(ring.walls[2].radius_m, 6 * kRadius);  // it closed in on the packing
}
