// Material genesis: the packing reaches the porosity, stays inside the box,
// carries no locked-in overlap, has no floaters, depends only on geometry and
// seed, and survives the HDF5 cache unchanged.
#include <gtest/gtest.h>

#include "../common/scratch.hpp"

#include <cmath>
#include <cstdio>
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
  // The servo walls relax the expansion's stress, so the box grows a little.
  EXPECT_NEAR(s.width_m, 0.01, 0.03 * 0.01);
  EXPECT_NEAR(s.height_m, 0.02, 0.03 * 0.02);
  EXPECT_NEAR(s.porosity, 0.16, 0.04);
  double worst_overlap = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_GE(s.x[i] - s.radius[i], -1e-12);
    EXPECT_LE(s.x[i] + s.radius[i], s.width_m + 1e-12);
    EXPECT_GE(s.y[i] - s.radius[i], -1e-12);
    EXPECT_LE(s.y[i] + s.radius[i], s.height_m + 1e-12);
    EXPECT_GT(s.radius[i], 0.95 * 3e-4);
    for (std::size_t j = i + 1; j < s.size(); ++j)
      worst_overlap = std::max(worst_overlap, s.radius[i] + s.radius[j] - std::hypot(s.x[j] - s.x[i], s.y[j] - s.y[i]));
  }
  EXPECT_LE(worst_overlap, 1e-12);  // no locked-in force
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
  // A different spec does not hit the same entry; a stale key is refused.
  SpecimenSpec other = small_spec(6);
  EXPECT_NE(spec.cache_key(), other.cache_key());
  std::string path = dir + "/probe.h5";
  save_specimen(packed, spec.cache_key(), path);
  EXPECT_THROW(load_specimen(path, other.cache_key()), demcal::Error);
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
