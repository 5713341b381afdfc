// Triangle meshes from STL: ASCII and binary read alike, closedness told,
// bad files refused naming the facet; a sphere resting on a meshed floor
// (on a facet, on the diagonal two facets share, on a corner four share)
// feels the floor once; a meshed box holds a sphere; a mesh moving up lifts a
// sphere at its speed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/stl_mesh.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650, kModulus = 1e9;

using Facet = std::array<Vec3, 3>;

// A square floor from (-h, -h) to (h, h) at z = 0 as four triangles meeting at the centre... as two triangles per
// quarter: 8 triangles, so the centre is a corner four facets share.
std::vector<Facet> floor_facets(double h) {
  std::vector<Facet> out;
  const Vec3 corners[4] = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  for (int q = 0; q < 4; ++q) out.push_back({Vec3{0, 0, 0}, corners[q], corners[(q + 1) % 4]});
  return out;
}

// A closed cube of side s from the origin: 12 facets, normals out.
std::vector<Facet> cube_facets(double s) {
  const Vec3 p[8] = {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0}, {0, 0, s}, {s, 0, s}, {s, s, s}, {0, s, s}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  std::vector<Facet> out;
  for (const auto& f : faces) {
    out.push_back({p[f[0]], p[f[1]], p[f[2]]});
    out.push_back({p[f[0]], p[f[2]], p[f[3]]});
  }
  return out;
}

std::string write_ascii(const std::string& name, const std::vector<Facet>& facets) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream out(path);
  out.precision(17);
  out << "solid test\n";
  for (const Facet& f : facets) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (const Vec3& v : f) out << "   vertex " << v.x << ' ' << v.y << ' ' << v.z << "\n";
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid test\n";
  return path;
}

std::string write_binary(const std::string& name, const std::vector<Facet>& facets) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream out(path, std::ios::binary);
  char header[80] = "solid but binary";  // a binary file may begin with "solid": the size tells
  out.write(header, 80);
  const auto count = static_cast<std::uint32_t>(facets.size());
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (const Facet& f : facets) {
    float values[12] = {0, 0, 0};
    for (int v = 0; v < 3; ++v) {
      values[3 + 3 * v] = static_cast<float>(f[static_cast<std::size_t>(v)].x);
      values[4 + 3 * v] = static_cast<float>(f[static_cast<std::size_t>(v)].y);
      values[5 + 3 * v] = static_cast<float>(f[static_cast<std::size_t>(v)].z);
    }
    out.write(reinterpret_cast<const char*>(values), 48);
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), 2);
  }
  return path;
}

World world_with(const std::vector<Wall>& triangles, Vec3 sphere_at) {
  WorldSettings settings;
  settings.gravity_m_s2 = {0, 0, -9.81};
  World world(settings);
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", kModulus}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  world.walls = triangles;
  world.spheres.add_sphere(sphere_at, kRadius, kDensity, 0);
  return world;
}

}  // namespace

TEST(Meshes3D, AsciiAndBinaryStlReadAlikeAndClosednessIsTold) {
  const StlMesh ascii = read_stl(write_ascii("cube.stl", cube_facets(0.01)), 0);
  const StlMesh binary = read_stl(write_binary("cube.bin.stl", cube_facets(0.01)), 0);
  ASSERT_EQ(ascii.triangles.size(), 12u);
  ASSERT_EQ(binary.triangles.size(), 12u);
  EXPECT_TRUE(ascii.closed);
  EXPECT_TRUE(binary.closed);
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(binary.triangles[5].vertices[v].z, ascii.triangles[5].vertices[v].z, 1e-9);
  EXPECT_FALSE(read_stl(write_ascii("floor.stl", floor_facets(0.01)), 1).closed);
  // Millimetres read as metres, shifted.
  const StlMesh mm = read_stl(write_ascii("cube_mm.stl", cube_facets(10)), 0, 1, 0.001, {0, 0, 1});
  EXPECT_NEAR(mm.triangles[2].vertices[2].z, 1.0 + (mm.triangles[2].vertices[2].z - 1.0), 1e-12);
  EXPECT_NEAR(mm.triangles[0].point_m.z, 1.005, 1e-12);  // the pivot: the centroid of the corners
}

TEST(Meshes3D, BadStlFilesAreRefusedNamingTheFacet) {
  auto message = [](const std::string& path, bool closed) {
    try {
      read_stl(path, 0, 1, 1.0, {}, closed);
    } catch (const demcal::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::vector<Facet> nan = cube_facets(0.01);
  nan[3][1].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(write_binary("nan.stl", nan), false).find("facet 4 has a coordinate that is not a finite number"),
            std::string::npos);
  // A facet without area (a sliver: its corners in a line) is left out with a warning, its edges still counted.
  std::vector<Facet> sliver = cube_facets(0.01);
  sliver.push_back({Vec3{0, 0, 0}, Vec3{0.005, 0, 0}, Vec3{0.01, 0, 0}});
  const StlMesh kept = read_stl(write_ascii("sliver.stl", sliver), 0);
  EXPECT_EQ(kept.triangles.size(), 12u);
  EXPECT_EQ(kept.facets_without_area, 1u);
  std::vector<Facet> open = cube_facets(0.01);
  open.pop_back();
  EXPECT_NE(message(write_ascii("open.stl", open), true).find("the mesh is not closed (3 edges"), std::string::npos);
  EXPECT_NE(message(::testing::TempDir() + "missing.stl", false).find("cannot open the STL file"), std::string::npos);
  std::ofstream(::testing::TempDir() + "text.stl") << "hello\n";
  EXPECT_NE(message(::testing::TempDir() + "text.stl", false).find("not an STL file"), std::string::npos);
}

// On a facet, on an edge two facets share and on the corner four share, the floor pushes once: the same static
// overlap m g / kn as on a plane (kn = pi R E for a sphere on a wall).
TEST(Meshes3D, ASphereOnAMeshedFloorFeelsItOnce) {
  const StlMesh floor = read_stl(write_ascii("floor.stl", floor_facets(0.01)), 1);
  for (const Vec3 at : {Vec3{0.004, 0.001, 0}, Vec3{0.003, 0.003, 0}, Vec3{0, 0, 0}}) {
    World world = world_with(floor.triangles, {at.x, at.y, kRadius * 1.0005});
    world.run(30000);
    const double m = world.spheres.mass[0], kn = M_PI * kRadius * kModulus;
    EXPECT_NEAR(kRadius - world.spheres.z[0], m * 9.81 / kn, 1e-3 * m * 9.81 / kn) << at.x << ", " << at.y;
    EXPECT_NEAR(mesh_force_n(world.walls, 1).z, -m * 9.81, 1e-3 * m * 9.81) << at.x << ", " << at.y;
  }
}

TEST(Meshes3D, AMeshedBoxHoldsASphereAndAMovingFloorLiftsIt) {
  const StlMesh box = read_stl(write_binary("box.stl", cube_facets(0.01)), 2, 1, 1.0, {}, true);
  World world = world_with(box.triangles, {0.005, 0.005, 0.005});
  world.spheres.set_velocity(0, {0.3, -0.2, 0.1});
  while (world.time_s() < 0.5) world.step();
  const Vec3 p = world.spheres.position(0);
  for (double v : {p.x, p.y, p.z}) {
    EXPECT_GT(v, 0.9 * kRadius);
    EXPECT_LT(v, 0.01 - 0.9 * kRadius);
  }
  EXPECT_NEAR(p.z, kRadius, 0.01 * kRadius);  // at rest on the bottom
  // The whole box rises at 1 cm/s: the sphere rides on its floor at that speed.
  set_mesh_motion(world.walls, 2, {0, 0, 0.01}, {}, {0.005, 0.005, 0.005});
  const double start = world.time_s();
  while (world.time_s() < start + 0.05) world.step();
  const double z0 = world.spheres.z[0], t0 = world.time_s();
  while (world.time_s() < start + 0.1) world.step();
  // On average over 0.05 s (the sphere rings on its contact after the box starts), the box's speed.
  EXPECT_NEAR((world.spheres.z[0] - z0) / (world.time_s() - t0), 0.01, 1e-4);
  EXPECT_NEAR(world.spheres.z[0] - world.walls[0].vertices[0].z, kRadius, 0.01 * kRadius);
}
