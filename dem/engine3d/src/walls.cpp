#include "demcal/dem3d/walls.hpp"

#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem3d {

namespace {

Vec3 unit(Vec3 v, const char* what) {
  const double length = norm(v);
  if (!(length > 0) || !std::isfinite(length)) throw Error(std::string(what) + " needs a direction of nonzero length");
  return (1.0 / length) * v;
}

}  // namespace

WallContact Wall::contact(Vec3 centre_m, double r) const {
  WallContact c;
  const Vec3 from_point = centre_m - point_m;
  if (shape == WallShape::plane) {
    const double distance = dot(from_point, axis);
    c.overlap_m = r - distance;
    c.normal = -axis;
  } else {
    const double along = dot(from_point, axis);
    if (length_m > 0 && (along < 0 || along > length_m)) return c;  // beyond its ends (no caps)
    const Vec3 radial = from_point - along * axis;
    const double rho = norm(radial);
    if (!(rho > 0)) return c;  // on the axis: no direction to push along
    const Vec3 outward = (1.0 / rho) * radial;
    if (shape == WallShape::cylinder_inside) {
      c.overlap_m = r - (radius_m - rho);
      c.normal = outward;
    } else {
      c.overlap_m = r - (rho - radius_m);
      c.normal = -outward;
    }
  }
  c.point_m = centre_m + (r - 0.5 * c.overlap_m) * c.normal;
  return c;
}

Wall make_plane(Vec3 point_m, Vec3 normal, std::uint8_t group) {
  Wall w;
  w.shape = WallShape::plane;
  w.point_m = point_m;
  w.axis = unit(normal, "a plane wall");
  w.group = group;
  return w;
}

Wall make_cylinder(Vec3 base_m, Vec3 axis, double radius_m, double length_m, bool inside, std::uint8_t group) {
  if (!(radius_m > 0) || !std::isfinite(radius_m))
    throw Error("a cylinder wall needs radius_m > 0 (got " + format_double(radius_m) + ")");
  if (!(length_m >= 0) || !std::isfinite(length_m))
    throw Error("a cylinder wall needs length_m >= 0 (0: unbounded; got " + format_double(length_m) + ")");
  Wall w;
  w.shape = inside ? WallShape::cylinder_inside : WallShape::cylinder_outside;
  w.point_m = base_m;
  w.axis = unit(axis, "a cylinder wall");
  w.radius_m = radius_m;
  w.length_m = length_m;
  w.group = group;
  return w;
}

}  // namespace demcal::dem3d
