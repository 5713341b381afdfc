#include "demcal/dem3d/walls.hpp"

#include <algorithm>
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

namespace {

// The point of triangle (a, b, c) closest to p, and which feature it lies on
// (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c, WallFeature& feature) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  feature = WallFeature::vertex;
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  feature = WallFeature::edge;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  feature = WallFeature::face;
  const double denominator = 1.0 / (va + vb + vc);
  return a + (vb * denominator) * ab + (vc * denominator) * ac;
}

}  // namespace

WallContact Wall::contact(Vec3 centre_m, double r) const {
  WallContact c;
  const Vec3 from_point = centre_m - point_m;
  if (shape == WallShape::triangle) {
    WallFeature feature;
    const Vec3 closest = closest_on_triangle(centre_m, vertices[0], vertices[1], vertices[2], feature);
    const Vec3 towards = closest - centre_m;
    const double distance = norm(towards);
    if (!(distance > 0)) return c;  // the centre on the facet: no direction to push along
    c.overlap_m = r - distance;
    c.normal = (1.0 / distance) * towards;
    c.feature = feature;
    c.point_m = centre_m + (r - 0.5 * c.overlap_m) * c.normal;
    return c;
  }
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

Vec3 Wall::velocity_at(Vec3 p) const {
  Vec3 v = velocity_m_s + cross(spin_rad_s, p - point_m);
  if (radial_speed_m_s != 0 && (shape == WallShape::cylinder_inside || shape == WallShape::cylinder_outside)) {
    const Vec3 from_axis = (p - point_m) - dot(p - point_m, axis) * axis;
    const double rho = norm(from_axis);
    if (rho > 0) v = v + (radial_speed_m_s / rho) * from_axis;
  }
  return v;
}

double Wall::loaded_area_m2() const {
  if (servo_area_m2 > 0) return servo_area_m2;
  if ((shape == WallShape::cylinder_inside || shape == WallShape::cylinder_outside) && length_m > 0)
    return 2 * M_PI * radius_m * length_m;
  return 0;
}

Vec3 closest_point_on_triangle(const Wall& t, Vec3 p) {
  WallFeature feature;
  return closest_on_triangle(p, t.vertices[0], t.vertices[1], t.vertices[2], feature);
}

Wall make_triangle(Vec3 a, Vec3 b, Vec3 c, std::int32_t mesh, Vec3 pivot_m, std::uint8_t group) {
  for (const Vec3& v : {a, b, c})
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw Error("a triangle has a corner that is not a finite point");
  const Vec3 normal = cross(b - a, c - a);
  const double twice_area = norm(normal);
  if (!(twice_area > 1e-12 * std::max({dot(b - a, b - a), dot(c - a, c - a), 1e-300})))
    throw Error("a triangle spans no area (its corners are in a line)");
  Wall w;
  w.shape = WallShape::triangle;
  w.vertices[0] = a, w.vertices[1] = b, w.vertices[2] = c;
  w.axis = (1.0 / twice_area) * normal;
  w.mesh = mesh;
  w.point_m = pivot_m;
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
