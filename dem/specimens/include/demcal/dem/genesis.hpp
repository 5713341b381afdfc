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
  double porosity = 0.16;           // target 2D porosity after expansion
  double radius_min_m = 0.5e-3;
  double radius_max_m = 0.75e-3;    // radii uniform in [min, max]
  double density_kg_m3 = 2650;
  std::uint64_t seed = 1;
  // Genesis settings (fixed, so packings do not depend on calibrated values)
  double genesis_modulus_pa = 1e9;      // frictionless linear contacts while packing
  double isotropic_stress_pa = 1e5;     // locked-in stress installed by servo walls
  double stress_tolerance = 0.05;       // relative, for the servo stage
  int min_contacts = 3;                 // fewer makes a floater

  // Number of disks: floor(W H (1 - n) / (pi R_mean^2)).
  std::size_t disk_count() const;
  // Text that identifies the packing (geometry, genesis settings, seed).
  std::string cache_key() const;
  void validate() const;  // throws an Error naming the field
};

struct Specimen {
  std::vector<double> x, y, radius;  // m, inside [0, width] x [0, height]
  double width_m = 0, height_m = 0, thickness_m = 1, density_kg_m3 = 0;
  double porosity = 0;               // achieved
  std::size_t floaters_removed = 0;
  std::uint64_t steps = 0;           // cycles spent packing
  std::size_t size() const { return x.size(); }
};

// Packs a specimen: disks at random positions with reduced radii, expanded in
// stages by m = sqrt((1 - n) / (1 - n0)) to the target porosity and cycled to
// equilibrium frictionless inside four walls; servo walls then install the
// isotropic stress; floaters are grown, and removed when that fails. Last,
// each disk shrinks by its share of its largest overlap, so the specimen
// carries no locked-in force whatever stiffness the test gives it (the gaps
// left are far below the bond-installation tolerance).
Specimen pack_specimen(const SpecimenSpec& spec);

// The cached packing for `spec` under `cache_dir` (HDF5), packing and storing
// it first when absent. An empty cache_dir packs without caching.
Specimen cached_specimen(const SpecimenSpec& spec, const std::string& cache_dir);

void save_specimen(const Specimen& specimen, const std::string& key, const std::string& path);
// Throws when the file's key differs from `key` (a stale or foreign cache).
Specimen load_specimen(const std::string& path, const std::string& key);

}  // namespace demcal::dem
