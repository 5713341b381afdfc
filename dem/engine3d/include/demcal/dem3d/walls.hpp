#pragma once
// Walls of the 3D engine: planes, cylinders and the triangles of meshes (read
// from STL: stl_mesh.hpp), each moving at a set velocity and spinning about
// its reference point at a set rate, and collecting the force and moment the
// spheres exert on it.
//
// A contact model never sees a wall's shape: the world turns every
// sphere-wall pair into a contact geometry (WallContact: the normal from the
// sphere to the wall, the overlap, the wall's velocity at the contact point),
// so a new wall shape needs no change in any model.
#include <cstdint>
#include <vector>

#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

enum class WallShape : std::uint8_t {
  plane,            // through point_m, axis = unit normal into the domain
  cylinder_inside,  // spheres inside: axis through point_m, radius_m, length_m along axis (0: unbounded)
  cylinder_outside,  // spheres outside (a rod)
  triangle           // one facet of a mesh: vertices[0..2], axis = its unit normal; touched from either side
};

// Where on a wall element the closest point lies: a triangle's face, an edge
// or a vertex (planes and cylinders: always the face). A sphere touching a
// mesh keeps every face contact but only one contact per shared edge or
// vertex point (World, mesh_contacts.cpp).
enum class WallFeature : std::uint8_t { face, edge, vertex };

// What a sphere sees of a wall.
struct WallContact {
  double overlap_m = -1e300;  // > 0 in contact; the gap when negative
  Vec3 normal;                // unit, from the sphere's centre towards the wall
  Vec3 point_m;               // the contact point (middle of the overlap)
  WallFeature feature = WallFeature::face;
};

struct Wall {
  WallShape shape = WallShape::plane;
  Vec3 point_m;  // a plane's point, a cylinder's base; a mesh's pivot (it spins about it)
  Vec3 axis;     // unit
  double radius_m = 0;
  double length_m = 0;
  Vec3 vertices[3];       // a triangle's corners, m
  std::int32_t mesh = -1;  // the mesh a triangle belongs to (-1: none)
  Vec3 velocity_m_s;
  Vec3 spin_rad_s;  // about point_m
  std::uint8_t group = 1;
  bool active = true;
  Vec3 force_n;    // the spheres' force on the wall at the last step
  Vec3 moment_nm;  // and their moment about point_m
  // The sum of the spheres' pushes along each contact's normal at the last
  // step, N: what a servo measures (a cylinder's radial forces cancel in force_n).
  double normal_force_n = 0;

  // Servo control to a stress: a plane moves along its axis, a cylinder
  // changes its radius, at speed gain x (measured - target) stress away from
  // the spheres (towards them when below), capped at servo_max_speed_m_s. A
  // gain of 0 takes PFC's rule each step: half the stress error closed
  // against the stiffness of the contacts on the wall, 0.5 A / (k dt).
  bool servo = false;
  double servo_target_stress_pa = 0;
  double servo_area_m2 = 0;  // a plane's loaded area; 0 for a cylinder: 2 pi R L (its length must be set)
  double servo_gain_m_s_per_pa = 0;
  double servo_max_speed_m_s = 0;
  double radial_speed_m_s = 0;  // a cylinder's radius grows at this rate (a servo sets it)

  WallContact contact(Vec3 centre_m, double radius_m) const;
  // The wall's velocity at `p` (its translation, its spin about point_m and a
  // cylinder's radial growth).
  Vec3 velocity_at(Vec3 p) const;
  // The area a servo divides its force by.
  double loaded_area_m2() const;
};

// A plane through `point_m` with inward normal `normal` (normalised here; an
// Error when it has no length).
Wall make_plane(Vec3 point_m, Vec3 normal, std::uint8_t group = 1);
// A cylinder whose axis runs from `base_m` along `axis` for `length_m` (0:
// unbounded), radius `radius_m` (an Error when not > 0); spheres inside it,
// or outside when `inside` is false.
Wall make_cylinder(Vec3 base_m, Vec3 axis, double radius_m, double length_m, bool inside = true,
                   std::uint8_t group = 1);
// The point of triangle `t` (a WallShape::triangle) closest to p.
Vec3 closest_point_on_triangle(const Wall& t, Vec3 p);

// A triangle of mesh `mesh` with corners a, b, c (an Error when they are not
// finite or span no area); it spins about `pivot_m`.
Wall make_triangle(Vec3 a, Vec3 b, Vec3 c, std::int32_t mesh, Vec3 pivot_m, std::uint8_t group = 1);

}  // namespace demcal::dem3d
