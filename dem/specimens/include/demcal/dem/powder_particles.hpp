#pragma once
// Loose particles for a powder test (a heap poured from a funnel): disks and
// two-disk clumps placed at random, without overlap, in a convex region, until
// they cover a set fraction of it.
//
// A clump of aspect ratio AR is two equal disks of radius r whose centres lie
// 2 r (AR - 1) apart, so its length over its width is AR (the seed's 1.3). It
// moves as one rigid body with the mass and inertia of the union of its disks
// (the overlap counted once), at the world's thickness.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace demcal::dem {

class World;

struct PowderSpec {
  double radius_min_m = 0, radius_max_m = 0;  // each particle's disk radius, uniform in [min, max]
  double density_kg_m3 = 0;
  double clump_aspect_ratio = 1.0;            // 1: disks; > 1: two-disk clumps of this length over width
  double clump_fraction = 1.0;                // share of the particles that are clumps (when the ratio is > 1)
  double solids_fraction = 0.4;              // area of the particles over the region's
  int max_attempts_per_particle = 2000;
  void validate(const char* where) const;     // throws an Error naming `where` and the field
};

struct PowderParticle {
  double x = 0, y = 0;       // centre (of mass), m
  double radius = 0;         // its disks' radius, m
  double angle_rad = 0;      // a clump's axis
  bool clump = false;
};

// Places particles in the convex polygon `region` (vertices counter-clockwise,
// x then y, m) until they cover spec.solids_fraction of its area; every disk
// lies wholly inside. Throws an Error when the fraction cannot be reached.
std::vector<PowderParticle> place_powder(const PowderSpec& spec, const std::vector<double>& region_xy,
                                         std::uint64_t seed);

// Area and polar moment of inertia (about the centroid) of a particle's shape
// per unit thickness, for disk radius r: a disk's pi r^2 and pi r^4 / 2, a
// clump's union of two disks.
double particle_area_m2(double radius_m, double aspect_ratio, bool clump);
double particle_polar_moment_m4(double radius_m, double aspect_ratio, bool clump);

// Adds the particles to the world (material group `group`): a disk as a disk,
// a clump as two member disks made one rigid body. Their disks' ids follow the
// particles' order whatever order they enter in (`order_seed` shuffles it, 0
// keeps it: results must not depend on it). Returns the number of disks added.
std::size_t add_powder(World& world, const std::vector<PowderParticle>& particles, const PowderSpec& spec,
                       double thickness_m, std::uint8_t group, std::uint64_t order_seed = 0);

}  // namespace demcal::dem
