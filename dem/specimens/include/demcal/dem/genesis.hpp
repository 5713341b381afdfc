#pragma once
// Material genesis (as PFC users know it): a packed, bonded-ready specimen
// built by radius expansion inside walls. The packing depends only on the
// geometry and the seed, never on the stiffness or strength being calibrated,
// so it is cached and reused by every design point that shares them.
#include <cstdint>
#include <string>
#include <vector>

namespace demcal::dem {

struct SpecimenSpec {
  double width_m = 0.05;
  double height_m = 0.1;
  double thickness_m = 1.0;
  double porosity = 0.16;           // 2D porosity 1 - sum(pi r^2) / (W H), overlaps counted as PFC does
  double radius_min_m = 0.5e-3;
  double radius_max_m = 0.75e-3;    // radii uniform in [min, max]
  double density_kg_m3 = 2650;
  std::uint64_t seed = 1;
  // Genesis settings (fixed, so packings do not depend on calibrated values)
  double genesis_modulus_pa = 1e9;      // frictionless linear contacts while packing
  // > 0: servo walls install this isotropic stress after expansion (P&C
  // 2004), and the porosity is then an outcome; 0: the vessel stays fixed
  // and the porosity is the one asked (PFC's `ball distribute`).
  double isotropic_stress_pa = 0;
  double stress_tolerance = 0.05;       // relative, for the servo stage
  int min_contacts = 3;                 // fewer makes a floater
  // Not part of the packing (nor of its cache key): the mean stress the
  // contacts keep when bonds are installed (0: force-free, as PFC 6's
  // material genesis leaves them). May depend on the point's parameters.
  double locked_in_stress_pa = 0;

  // Number of disks: floor(W H (1 - n) / (pi R_mean^2)).
  std::size_t disk_count() const;
  // Text that identifies the packing (geometry, genesis settings, seed).
  std::string cache_key() const;
  void validate() const;  // throws an Error naming the field
};

struct Specimen {
  std::vector<double> x, y, radius;  // m, inside [0, width] x [0, height]
  double width_m = 0, height_m = 0, thickness_m = 1, density_kg_m3 = 0;
  double porosity = 0;               // achieved, overlaps not subtracted
  double coordination_number = 0;    // disk-disk contacts per disk
  double mean_overlap_ratio = 0;     // mean overlap / smaller radius over those contacts
  std::size_t floaters_removed = 0;
  std::uint64_t steps = 0;           // cycles spent packing
  std::size_t size() const { return x.size(); }
};

// Packs a specimen as PFC does: disks at random positions with reduced radii,
// expanded in stages by m = sqrt((1 - n) / (1 - n0)) to the asked porosity and
// cycled to equilibrium frictionless inside four fixed walls (servo walls to
// an isotropic stress instead when the spec asks for one); floaters are
// grown, and removed when that fails. The disks keep their overlaps: below
// random close packing (about 0.16 for these size ranges) a porosity needs
// them. They never become forces in a test, because bonding makes every
// overlapping pair force-free as it lies (World::install_bonds). In a fixed
// vessel, a porosity more than 0.005 from the one asked is an Error.
Specimen pack_specimen(const SpecimenSpec& spec);

// The cached packing for `spec` under `cache_dir` (HDF5), packing and storing
// it first when absent. An empty cache_dir packs without caching.
Specimen cached_specimen(const SpecimenSpec& spec, const std::string& cache_dir);

void save_specimen(const Specimen& specimen, const std::string& key, const std::string& path);
// Throws when the file's key differs from `key` (a stale or foreign cache).
Specimen load_specimen(const std::string& path, const std::string& key);

}  // namespace demcal::dem
