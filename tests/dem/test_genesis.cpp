// Material genesis: the packing reaches the porosity asked (overlaps and all,
// as PFC counts it), stays inside the box, has no floaters, depends only on
// geometry and seed, and survives the HDF5 cache unchanged. That bonding makes
// it force-free is test_force_free_installation.cpp.
#include <gtest/gtest.h>

#include "../common/error_of.hpp"
#include "../common/scratch.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <unistd.h>

#include "demcal/core/error.hpp"
#include "demcal/dem/genesis.hpp"

using namespace demcal::dem;

namespace {

SpecimenSpec small_spec(std::uint64_t seed) {
  SpecimenSpec spec;
  spec.width_m = 0.01;
  spec.height_m = 0.02;
  spec.radius_min_m = 3e-4;
  spec.radius_max_m = 4.5e-4;
  spec.density_kg_m3 = 2000;
  spec.seed = seed;
  return spec;
}

}  // namespace

TEST(Genesis, PackingMeetsItsSpecification) {
  SpecimenSpec spec = small_spec(1);
  Specimen s = pack_specimen(spec);
  // N = floor(W H (1 - n) / (pi R_mean^2)), less the floaters that could not be fixed.
  EXPECT_EQ(spec.disk_count(), static_cast<std::size_t>(std::floor(0.01 * 0.02 * 0.84 / (M_PI * 3.75e-4 * 3.75e-4))));
  EXPECT_EQ(s.size() + s.floaters_removed, spec.disk_count());
  EXPECT_LT(s.floaters_removed, spec.disk_count() / 20);
  // The vessel stays fixed, so the porosity (PFC's count: overlaps not
  // subtracted) is the one asked, less what the floaters took away.
  EXPECT_EQ(s.width_m, 0.01);
  EXPECT_EQ(s.height_m, 0.02);
  EXPECT_NEAR(s.porosity, 0.16, 0.005);
  double solid = 0;
  for (std::size_t i = 0; i < s.size(); ++i) solid += M_PI * s.radius[i] * s.radius[i];
  EXPECT_NEAR(s.porosity, 1 - solid / (0.01 * 0.02), 1e-12);
  for (std::size_t i = 0; i < s.size(); ++i) {
    // Centres inside the box; a disk may press into a wall by a small overlap.
    EXPECT_GE(s.x[i] - s.radius[i], -0.05 * s.radius[i]);
    EXPECT_LE(s.x[i] + s.radius[i], s.width_m + 0.05 * s.radius[i]);
    EXPECT_GE(s.y[i] - s.radius[i], -0.05 * s.radius[i]);
    EXPECT_LE(s.y[i] + s.radius[i], s.height_m + 0.05 * s.radius[i]);
    EXPECT_GT(s.radius[i], 0.95 * 3e-4);
  }
  // A jammed 2D packing: every kept disk has at least 3 contacts, so at least
  // 3 per disk on average, with overlaps a small fraction of a radius.
  EXPECT_GE(s.coordination_number, 3.0);
  EXPECT_LT(s.coordination_number, 6.0);
  EXPECT_GT(s.mean_overlap_ratio, 0.0);
  EXPECT_LT(s.mean_overlap_ratio, 0.05);
}

TEST(Genesis, BelowRandomClosePackingThePorosityComesFromOverlaps) {
  // 0.12 lies below the random close packing of these disks (about 0.16):
  // PFC reaches it with overlapping disks, and so does genesis now.
  SpecimenSpec spec = small_spec(2);
  spec.porosity = 0.12;
  Specimen dense = pack_specimen(spec);
  Specimen loose = pack_specimen(small_spec(2));
  EXPECT_NEAR(dense.porosity, 0.12, 0.005);
  EXPECT_GT(dense.mean_overlap_ratio, loose.mean_overlap_ratio);
  EXPECT_GT(dense.coordination_number, loose.coordination_number);
}

TEST(Genesis, ServoWallsMakeThePorosityAnOutcome) {
  // With an isotropic stress asked for (Potyondy & Cundall 2004), servo walls
  // move until the walls carry it: at 0.12 asked the box opens up towards
  // random close packing, and the porosity reported is what it became.
  SpecimenSpec spec = small_spec(2);
  spec.porosity = 0.12;
  spec.isotropic_stress_pa = 1e5;
  Specimen s = pack_specimen(spec);
  EXPECT_GT(s.width_m * s.height_m, 1.02 * 0.01 * 0.02);
  EXPECT_GT(s.porosity, 0.14);
  double solid = 0;
  for (std::size_t i = 0; i < s.size(); ++i) solid += M_PI * s.radius[i] * s.radius[i];
  EXPECT_NEAR(s.porosity, 1 - solid / (s.width_m * s.height_m), 1e-12);
  spec.isotropic_stress_pa = -1;
  EXPECT_THROW(spec.validate(), demcal::Error);
}

TEST(Genesis, SameSeedSamePackingOtherSeedAnother) {
  Specimen a = pack_specimen(small_spec(3)), b = pack_specimen(small_spec(3)), c = pack_specimen(small_spec(4));
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_NE(a.x, c.x);
}

TEST(Genesis, CacheStoresAndReloadsTheSamePacking) {
  std::string dir = demcal::test::scratch_path("cache");
  SpecimenSpec spec = small_spec(5);
  Specimen packed = cached_specimen(spec, dir);
  Specimen loaded = cached_specimen(spec, dir);  // from the file this time
  EXPECT_EQ(packed.x, loaded.x);
  EXPECT_EQ(packed.radius, loaded.radius);
  EXPECT_EQ(packed.porosity, loaded.porosity);
  EXPECT_EQ(packed.coordination_number, loaded.coordination_number);
  EXPECT_EQ(packed.mean_overlap_ratio, loaded.mean_overlap_ratio);
  // A different spec does not hit the same entry; a stale key is refused.
  SpecimenSpec other = small_spec(6);
  EXPECT_NE(spec.cache_key(), other.cache_key());
  std::string path = dir + "/probe.h5";
  save_specimen(packed, spec.cache_key(), path);
  EXPECT_THROW(load_specimen(path, other.cache_key()), demcal::Error);
}

// A cache named relative to another folder than the repository's (build/cache
// from /tmp) has no parent yet: it is made; one under a file cannot be, and
// says so (it used to say an HDF5 file could not be opened).
TEST(Genesis, CacheMakesItsFolderWithParentsOrSaysWhyItCannot) {
  const std::string root = demcal::test::scratch_path("cache_parents");
  const SpecimenSpec spec = small_spec(5);
  const Specimen packed = cached_specimen(spec, root + "/build/cache");
  std::ostringstream entry;
  entry << root << "/build/cache/specimen_" << std::hex << std::hash<std::string>{}(spec.cache_key()) << ".h5";
  ASSERT_EQ(::access(entry.str().c_str(), R_OK), 0) << entry.str();
  EXPECT_EQ(cached_specimen(spec, root + "/build/cache").x, packed.x);
  const std::string file = root + "/a_file";
  std::FILE* f = std::fopen(file.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  const std::string message = demcal::test::error_of([&] { cached_specimen(spec, file + "/cache"); });
  EXPECT_NE(message.find("specimen cache " + file + "/cache: cannot create the folder ("), std::string::npos) << message;
}

TEST(Genesis, BadGeometryIsRejected) {
  SpecimenSpec spec = small_spec(1);
  spec.porosity = 0.7;
  EXPECT_THROW(spec.validate(), demcal::Error);
  spec = small_spec(1);
  spec.radius_max_m = 1e-4;  // below the minimum
  EXPECT_THROW(spec.validate(), demcal::Error);
  spec = small_spec(1);
  spec.width_m = -1;
  EXPECT_THROW(spec.validate(), demcal::Error);
}
