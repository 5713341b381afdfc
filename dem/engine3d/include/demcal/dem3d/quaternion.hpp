#pragma once
// Unit quaternions for the orientation of rigid bodies (clumps): q = (w, x,
// y, z) turns a body-frame vector into the world frame.
#include <cmath>

#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

struct Quaternion {
  double w = 1, x = 0, y = 0, z = 0;
};

inline Quaternion operator*(Quaternion a, Quaternion b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

inline Quaternion normalised(Quaternion q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}

// The rotation by |v| radians about v's direction (the identity for v = 0).
inline Quaternion rotation_by(Vec3 v) {
  const double angle = norm(v);
  if (!(angle > 0)) return {};
  const double s = std::sin(0.5 * angle) / angle;
  return {std::cos(0.5 * angle), s * v.x, s * v.y, s * v.z};
}

// q turns body-frame v into the world frame: q v q*.
inline Vec3 to_world(Quaternion q, Vec3 v) {
  const Vec3 u = {q.x, q.y, q.z};
  const Vec3 t = 2.0 * cross(u, v);
  return v + q.w * t + cross(u, t);
}

inline Vec3 to_body(Quaternion q, Vec3 v) { return to_world({q.w, -q.x, -q.y, -q.z}, v); }

}  // namespace demcal::dem3d
