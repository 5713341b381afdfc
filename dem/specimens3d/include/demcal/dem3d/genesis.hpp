#pragma once
// Material genesis in 3D, as PFC3D users know it: spheres at random positions
// in a vessel (a box or a cylinder), their radii expanded in stages to the
// asked porosity, cycled frictionless to equilibrium, floaters grown or
// removed. The packing depends only on the geometry and the seed, never on the
// parameters being calibrated, so it is cached and shared by every design
// point that has them.
#include <cstdint>
#include <string>
#include <vector>

namespace demcal::dem3d {

enum class Vessel : std::uint8_t { box, cylinder };

struct SphereSpecimenSpec {
  Vessel vessel = Vessel::box;
  double width_m = 0.05;   // box: along x; cylinder: its diameter
  double depth_m = 0.05;   // box: along y (a cylinder ignores it)
  double height_m = 0.1;   // along z
  double porosity = 0.36;  // 1 - sum(4/3 pi r^3) / V, overlaps counted as PFC does
  double radius_min_m = 1e-3;
  double radius_max_m = 1.5e-3;  // radii uniform in [min, max]
  double density_kg_m3 = 2650;
  std::uint64_t seed = 1;
  // Genesis settings (fixed, so packings do not depend on calibrated values).
  double genesis_modulus_pa = 1e9;  // frictionless linear contacts while packing
  int min_contacts = 4;             // fewer makes a floater (a sphere needs four to be held in 3D)

  double volume_m3() const;
  // floor(V (1 - n) / (4/3 pi E[r^3])) for radii uniform in [min, max].
  std::size_t sphere_count() const;
  // Text that identifies the packing (geometry, genesis settings, seed).
  std::string cache_key() const;
  void validate() const;  // throws an Error naming the field
};

struct SphereSpecimen {
  std::vector<double> x, y, z, radius;  // m; a box from (0, 0, 0), a cylinder on the z axis from z = 0
  Vessel vessel = Vessel::box;
  double width_m = 0, depth_m = 0, height_m = 0, density_kg_m3 = 0;
  double porosity = 0;              // achieved, overlaps not subtracted
  double coordination_number = 0;   // sphere-sphere contacts per sphere
  double mean_overlap_ratio = 0;    // mean overlap / smaller radius over those contacts
  std::size_t floaters_removed = 0;
  std::uint64_t steps = 0;          // cycles spent packing
  // The isotropic stress its contacts hold (the material-pressure stage,
  // material_pressure.hpp); 0 for a packing, whose overlaps bonding makes force-free.
  double locked_in_stress_pa = 0;
  std::size_t size() const { return x.size(); }
};

// Packs a specimen: staged radius expansion by ((1 - n) / (1 - n0))^(1/3) from
// a 25 % solid fraction, frictionless linear contacts at genesis_modulus_pa,
// the vessel fixed; floaters grown by up to 5 % and removed when that fails,
// the kept spheres scaled back to the porosity. The spheres keep their
// overlaps (a bonded test makes them force-free as they lie). A porosity more
// than 0.005 from the one asked, or a packing that did not jam (fewer than 3
// contacts per sphere: too loose for frictionless spheres), is an Error.
SphereSpecimen pack_sphere_specimen(const SphereSpecimenSpec& spec);

// Refuses (an Error) a packing that would need more than 80 % of the
// machine's memory (`machine_bytes`, or this machine's when 0), estimated at
// 1.9 kB per sphere, and says what a packing of 100k spheres or more will take.
void check_packing_memory(const SphereSpecimenSpec& spec, double machine_bytes = 0);

// The cached packing for `spec` under `cache_dir` (HDF5), packing and storing
// it first when absent (after check_packing_memory). An empty cache_dir packs
// without caching.
SphereSpecimen cached_sphere_specimen(const SphereSpecimenSpec& spec, const std::string& cache_dir);
void save_sphere_specimen(const SphereSpecimen& specimen, const std::string& key, const std::string& path);
// Throws when the file's key differs from `key` (a stale or foreign cache).
SphereSpecimen load_sphere_specimen(const std::string& path, const std::string& key);

}  // namespace demcal::dem3d
