#include "demcal/dem3d/walls.hpp"

#include <cmath>

#include "demcal/core/error.hpp"

namespace demcal::dem3d {

PlaneWall make_plane(Vec3 point_m, Vec3 normal, std::uint8_t group) {
  const double length = norm(normal);
  if (!(length > 0) || !std::isfinite(length)) throw Error("a plane wall needs a normal of nonzero length");
  PlaneWall wall;
  wall.point_m = point_m;
  wall.normal = (1.0 / length) * normal;
  wall.group = group;
  return wall;
}

}  // namespace demcal::dem3d
