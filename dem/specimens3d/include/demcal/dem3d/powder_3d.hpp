#pragma once
// Loose particles for a 3D powder test (a heap poured from a funnel): spheres
// and two-sphere clumps placed at random, without overlap, inside a vertical
// frustum (a funnel's inside) or an upright box, until they fill a set
// fraction of its volume.
//
// A clump of aspect ratio AR is two equal spheres of radius r whose centres lie
// 2 r (AR - 1) apart, so its length over its width is AR (He et al.'s 1.3). It
// moves as one rigid body with the mass and inertia of the union of its
// spheres, the shared lens counted once (exact, two_sphere_union).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "demcal/dem3d/quaternion.hpp"
#include "demcal/dem3d/vec3.hpp"

namespace demcal::dem3d {

class World;

struct PowderSpec3d {
  double radius_min_m = 0, radius_max_m = 0;  // each particle's sphere radius, uniform in [min, max]
  double density_kg_m3 = 0;
  double clump_aspect_ratio = 1.0;  // 1: spheres; > 1: two-sphere clumps of this length over width
  double clump_fraction = 1.0;      // share of the particles that are clumps (when the ratio is > 1)
  double solids_fraction = 0.25;    // volume of the particles over the region's
  int max_attempts_per_particle = 5000;
  // An Error naming `where` and the field.
  void validate(const std::string& where) const;
  // The longest particle, m.
  double longest_m() const { return 2 * radius_max_m * clump_aspect_ratio; }
};

// A frustum about the vertical axis x = y = 0: radius radius_bottom_m at
// z_bottom_m growing linearly to radius_top_m at z_top_m.
struct Frustum {
  double z_bottom_m = 0, z_top_m = 0, radius_bottom_m = 0, radius_top_m = 0;
  double volume_m3() const;
  // Whether a sphere of radius r at c lies wholly inside.
  bool holds(Vec3 c, double r) const;
};

// An upright box centred on the vertical axis: |x| <= half_x_m, |y| <= half_y_m, z_bottom_m <= z <= z_top_m.
struct UprightBox {
  double half_x_m = 0, half_y_m = 0, z_bottom_m = 0, z_top_m = 0;
  double volume_m3() const { return 4 * half_x_m * half_y_m * (z_top_m - z_bottom_m); }
  bool holds(Vec3 c, double r) const {
    return c.z - r >= z_bottom_m && c.z + r <= z_top_m && std::abs(c.x) + r <= half_x_m && std::abs(c.y) + r <= half_y_m;
  }
};

struct PowderParticle3d {
  Vec3 centre_m;            // centre of mass
  double radius_m = 0;      // its spheres' radius
  Quaternion orientation;   // body z is a clump's axis
  bool clump = false;
};

// Mass and principal moments of inertia (about the centre of mass: along the
// axis, and across it) of the union of two spheres of radius r whose centres
// lie d apart (0 <= d <= 2 r), solid at density rho; closed form.
struct TwoSphereUnion {
  double mass_kg = 0, axial_inertia_kg_m2 = 0, transverse_inertia_kg_m2 = 0;
};
TwoSphereUnion two_sphere_union(double radius_m, double centre_distance_m, double density_kg_m3);

// Places particles in `region` until they fill spec.solids_fraction of its
// volume; every sphere lies wholly inside. An Error (naming `where`) when the
// fraction cannot be reached.
std::vector<PowderParticle3d> place_powder_3d(const PowderSpec3d& spec, const Frustum& region, std::uint64_t seed,
                                              const std::string& where);
std::vector<PowderParticle3d> place_powder_3d(const PowderSpec3d& spec, const UprightBox& region, std::uint64_t seed,
                                              const std::string& where);

// The centres of a particle's spheres (one, or a clump's two).
std::vector<Vec3> member_centres(const PowderParticle3d& p, double aspect_ratio);

// Adds the particles to the world (material group `group`): a sphere as a
// sphere, a clump as two member spheres made one rigid body. Their spheres' ids
// follow the particles' order whatever order they enter in (`order_seed`
// shuffles it, 0 keeps it: results must not depend on it). Returns the
// number of spheres added.
std::size_t add_powder_3d(World& world, const std::vector<PowderParticle3d>& particles, const PowderSpec3d& spec,
                          std::uint8_t group, std::uint64_t order_seed = 0);

}  // namespace demcal::dem3d
