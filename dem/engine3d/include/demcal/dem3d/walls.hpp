#pragma once
// Walls of the 3D engine. A plane: a point and a unit normal pointing into
// the domain (the side the spheres are on), moving at a set velocity; it
// collects the forces the spheres exert on it. (Cylinders and triangle
// meshes join here.)
#include <cstdint>
#include <vector>

#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

struct PlaneWall {
  Vec3 point_m;
  Vec3 normal;  // unit, into the domain
  Vec3 velocity_m_s;
  std::uint8_t group = 1;
  bool active = true;
  Vec3 force_n;  // the spheres' force on the wall at the last step

  // Signed distance of `p` from the plane, positive on the domain's side, m.
  double distance_m(Vec3 p) const { return dot(p - point_m, normal); }
};

// A plane through `point_m` with normal `normal` (normalised here; an Error
// when it has no length).
PlaneWall make_plane(Vec3 point_m, Vec3 normal, std::uint8_t group = 1);

}  // namespace demcal::dem3d
