#include "demcal/dem3d/stl_mesh.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"

namespace demcal::dem3d {
namespace {

using Corners = std::array<Vec3, 3>;

std::vector<Corners> read_binary(const std::string& path, const std::string& bytes) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  std::vector<Corners> out(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* facet = bytes.data() + 84 + 50 * static_cast<std::size_t>(t) + 12;  // after the normal
    for (int v = 0; v < 3; ++v) {
      float xyz[3];
      std::memcpy(xyz, facet + 12 * v, 12);
      out[t][static_cast<std::size_t>(v)] = {xyz[0], xyz[1], xyz[2]};
    }
  }
  (void)path;
  return out;
}

std::vector<Corners> read_ascii(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  std::string word;
  std::vector<Corners> out;
  Corners facet;
  int corners = 0;
  while (in >> word) {
    if (word == "facet") {
      corners = 0;
    } else if (word == "vertex") {
      std::string x, y, z;
      if (!(in >> x >> y >> z)) throw Error(path + ": facet " + std::to_string(out.size() + 1) + ": a vertex needs three numbers");
      if (corners >= 3) throw Error(path + ": facet " + std::to_string(out.size() + 1) + ": more than three vertices");
      try {
        facet[static_cast<std::size_t>(corners++)] = {std::stod(x), std::stod(y), std::stod(z)};
      } catch (const std::exception&) {
        throw Error(path + ": facet " + std::to_string(out.size() + 1) + ": \"" + x + " " + y + " " + z +
                    "\" is not three numbers");
      }
    } else if (word == "endfacet") {
      if (corners != 3) throw Error(path + ": facet " + std::to_string(out.size() + 1) + ": not three vertices");
      out.push_back(facet);
    }
  }
  return out;
}

// The key of a corner for matching edges: the exact coordinates (an STL
// repeats each shared corner with the same numbers).
std::array<double, 3> key_of(Vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace

StlMesh read_stl(const std::string& path, std::int32_t mesh, std::uint8_t group, double scale, Vec3 offset_m,
                 bool must_be_closed) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot open the STL file");
  std::ostringstream buffer;
  buffer << file.rdbuf();
  const std::string bytes = buffer.str();
  std::vector<Corners> facets;
  std::uint32_t binary_count = 0;
  if (bytes.size() >= 84) std::memcpy(&binary_count, bytes.data() + 80, 4);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50 * static_cast<std::size_t>(binary_count))
    facets = read_binary(path, bytes);
  else if (bytes.compare(0, 5, "solid") == 0)
    facets = read_ascii(path, bytes);
  else
    throw Error(path + ": not an STL file (neither ASCII \"solid ...\" nor a binary file of 84 + 50 n bytes)");
  if (facets.empty()) throw Error(path + ": the STL file holds no facet");
  if (!(scale > 0) || !std::isfinite(scale)) throw Error(path + ": the scale must be a positive number");
  StlMesh out;
  Vec3 centroid;
  for (const Corners& f : facets)
    for (const Vec3& v : f) centroid = centroid + v;
  centroid = (1.0 / (3.0 * static_cast<double>(facets.size()))) * centroid;
  const Vec3 pivot = scale * centroid + offset_m;
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edges;
  for (std::size_t t = 0; t < facets.size(); ++t) {
    Corners c = facets[t];
    for (Vec3& v : c) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw Error(path + ": facet " + std::to_string(t + 1) + " has a coordinate that is not a finite number");
      v = scale * v + offset_m;
    }
    // Every edge counts for closedness, a sliver's too (its neighbours share them).
    for (int e = 0; e < 3; ++e) {
      auto a = key_of(c[static_cast<std::size_t>(e)]), b = key_of(c[static_cast<std::size_t>((e + 1) % 3)]);
      if (a == b) continue;  // two corners in one place: no edge
      if (b < a) std::swap(a, b);
      ++edges[{a, b}];
    }
    try {
      out.triangles.push_back(make_triangle(c[0], c[1], c[2], mesh, pivot, group));
    } catch (const Error&) {
      // A facet without area (CAD exports hold some) pushes nowhere: left out, and said below.
      ++out.facets_without_area;
    }
  }
  if (out.triangles.empty()) throw Error(path + ": every facet of the STL file spans no area");
  if (out.facets_without_area > 0)
    log::warn(path + ": " + std::to_string(out.facets_without_area) + " facet(s) without area left out");
  out.closed = true;
  for (const auto& [edge, uses] : edges) out.closed = out.closed && uses == 2;
  if (must_be_closed && !out.closed) {
    std::size_t open = 0;
    for (const auto& [edge, uses] : edges) open += uses != 2;
    throw Error(path + ": the mesh is not closed (" + std::to_string(open) +
                " edges are not shared by exactly two facets); a vessel must hold its contents");
  }
  return out;
}

void set_mesh_motion(std::vector<Wall>& walls, std::int32_t mesh, Vec3 velocity_m_s, Vec3 spin_rad_s, Vec3 pivot_m) {
  for (Wall& w : walls)
    if (w.shape == WallShape::triangle && w.mesh == mesh) {
      w.velocity_m_s = velocity_m_s;
      w.spin_rad_s = spin_rad_s;
      w.point_m = pivot_m;
    }
}

Vec3 mesh_force_n(const std::vector<Wall>& walls, std::int32_t mesh) {
  Vec3 sum;
  for (const Wall& w : walls)
    if (w.shape == WallShape::triangle && w.mesh == mesh) sum = sum + w.force_n;
  return sum;
}

}  // namespace demcal::dem3d
