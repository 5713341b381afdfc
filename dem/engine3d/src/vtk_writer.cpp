#include "demcal/dem3d/vtk_writer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "demcal/core/atomic_file.hpp"

namespace demcal::dem3d {

namespace {

void header(std::ostringstream& out, const char* what, double time_s) {
  out.precision(9);
  out << "# vtk DataFile Version 3.0\ndemcal " << what << " at t = " << time_s << " s\nASCII\nDATASET POLYDATA\n";
}

void point(std::ostringstream& out, Vec3 p) { out << p.x << ' ' << p.y << ' ' << p.z << '\n'; }

// Two unit vectors across `axis`.
void across(Vec3 axis, Vec3& u, Vec3& v) {
  const Vec3 other = std::abs(axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  u = cross(axis, other);
  u = (1.0 / norm(u)) * u;
  v = cross(axis, u);
}

}  // namespace

void write_vtk_spheres(const World& world, const std::string& path) {
  const Spheres& s = world.spheres;
  const dem::ContactSet& c = world.pairs();
  std::size_t bonds = 0;
  for (dem::PairFlags f : c.flags) bonds += (f & dem::kBonded) != 0;
  std::ostringstream out;
  header(out, "spheres", world.time_s());
  out << "POINTS " << s.size() << " double\n";
  for (std::size_t i = 0; i < s.size(); ++i) point(out, s.position(i));
  out << "VERTICES " << s.size() << ' ' << 2 * s.size() << '\n';
  for (std::size_t i = 0; i < s.size(); ++i) out << "1 " << i << '\n';
  out << "LINES " << bonds << ' ' << 3 * bonds << '\n';
  for (std::size_t k = 0; k < c.size(); ++k)
    if (c.flags[k] & dem::kBonded) out << "2 " << c.i[k] << ' ' << c.j[k] << '\n';
  out << "POINT_DATA " << s.size() << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (double r : s.radius) out << r << '\n';
  out << "SCALARS id int 1\nLOOKUP_TABLE default\n";
  for (std::uint32_t id : s.id) out << id << '\n';
  out << "VECTORS velocity double\n";
  for (std::size_t i = 0; i < s.size(); ++i) point(out, s.velocity(i));
  out << "VECTORS spin double\n";
  for (std::size_t i = 0; i < s.size(); ++i) point(out, s.spin(i));
  write_file_atomically(path, out.str());
}

void write_vtk_walls(const World& world, const std::string& path) {
  const Spheres& s = world.spheres;
  // How far to draw an unbounded wall: the spheres' extent (at least a metre
  // when there are none).
  double extent = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    extent = std::max({extent, std::abs(s.x[i]) + s.radius[i], std::abs(s.y[i]) + s.radius[i], std::abs(s.z[i]) + s.radius[i]});
  if (!(extent > 0)) extent = 1;
  constexpr int kFacets = 32;
  std::vector<Vec3> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::vector<std::size_t> owner;
  for (std::size_t w = 0; w < world.walls.size(); ++w) {
    const Wall& wall = world.walls[w];
    Vec3 u, v;
    across(wall.axis, u, v);
    if (wall.shape == WallShape::triangle) {
      const std::size_t first = points.size();
      for (const Vec3& v : wall.vertices) points.push_back(v);
      polygons.push_back({first, first + 1, first + 2});
      owner.push_back(w);
      continue;
    }
    if (wall.shape == WallShape::plane) {
      const std::size_t first = points.size();
      for (const auto& [a, b] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}})
        points.push_back(wall.point_m + (2 * extent) * ((a * u) + (b * v)));
      polygons.push_back({first, first + 1, first + 2, first + 3});
      owner.push_back(w);
      continue;
    }
    const double length = wall.length_m > 0 ? wall.length_m : 2 * extent;
    const Vec3 base = wall.length_m > 0 ? wall.point_m : wall.point_m - extent * wall.axis;
    const std::size_t first = points.size();
    for (int k = 0; k < kFacets; ++k) {
      const double a = 2 * M_PI * k / kFacets;
      const Vec3 radial = wall.radius_m * (std::cos(a) * u + std::sin(a) * v);
      points.push_back(base + radial);
      points.push_back(base + length * wall.axis + radial);
    }
    for (int k = 0; k < kFacets; ++k) {
      const std::size_t a = first + 2 * static_cast<std::size_t>(k), b = first + 2 * static_cast<std::size_t>((k + 1) % kFacets);
      polygons.push_back({a, b, b + 1, a + 1});
      owner.push_back(w);
    }
  }
  std::ostringstream out;
  header(out, "walls", world.time_s());
  out << "POINTS " << points.size() << " double\n";
  for (const Vec3& p : points) point(out, p);
  std::size_t size = 0;
  for (const auto& p : polygons) size += p.size() + 1;
  out << "POLYGONS " << polygons.size() << ' ' << size << '\n';
  for (const auto& p : polygons) {
    out << p.size();
    for (std::size_t k : p) out << ' ' << k;
    out << '\n';
  }
  out << "CELL_DATA " << polygons.size() << "\nSCALARS wall int 1\nLOOKUP_TABLE default\n";
  for (std::size_t w : owner) out << w << '\n';
  out << "SCALARS active int 1\nLOOKUP_TABLE default\n";
  for (std::size_t w : owner) out << (world.walls[w].active ? 1 : 0) << '\n';
  out << "VECTORS force double\n";
  for (std::size_t w : owner) point(out, world.walls[w].force_n);
  write_file_atomically(path, out.str());
}

}  // namespace demcal::dem3d
