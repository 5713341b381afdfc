// 3D genesis: the asked porosity in a box and in a cylinder, every kept sphere
// inside its vessel, contacts enough to hold them, the same packing from the
// cache, and bad specs refused naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/genesis.hpp"

using namespace demcal::dem3d;

namespace {

SphereSpecimenSpec small(Vessel vessel) {
  SphereSpecimenSpec spec;
  spec.vessel = vessel;
  spec.width_m = spec.depth_m = 0.009;  // about 480 spheres: a few seconds to pack
  spec.height_m = 0.018;
  spec.radius_min_m = 0.6e-3;
  spec.radius_max_m = 0.9e-3;
  spec.porosity = 0.40;
  return spec;
}

}  // namespace

TEST(Genesis3D, ReachesThePorosityInsideItsVessel) {
  for (Vessel vessel : {Vessel::box, Vessel::cylinder}) {
    const SphereSpecimenSpec spec = small(vessel);
    const SphereSpecimen s = pack_sphere_specimen(spec);
    EXPECT_NEAR(s.porosity, spec.porosity, 0.005);
    EXPECT_GT(s.size(), 0.95 * static_cast<double>(spec.sphere_count()));
    // A frictionless packing at this porosity holds each sphere by four or more contacts on average.
    EXPECT_GT(s.coordination_number, 4.0);
    EXPECT_LT(s.mean_overlap_ratio, 0.05);
    // The kept spheres are the held ones: hardly any has fewer than three sphere contacts (the rest lean on walls).
    std::vector<int> contacts(s.size(), 0);
    for (std::size_t a = 0; a < s.size(); ++a)
      for (std::size_t b = a + 1; b < s.size(); ++b)
        if (std::hypot(s.x[b] - s.x[a], s.y[b] - s.y[a], s.z[b] - s.z[a]) < s.radius[a] + s.radius[b]) ++contacts[a], ++contacts[b];
    EXPECT_LT(std::count_if(contacts.begin(), contacts.end(), [](int c) { return c < 3; }), 0.05 * static_cast<double>(s.size()));
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double reach = 0.2 * s.radius[i];  // overlaps with the vessel stay small
      EXPECT_GT(s.z[i], s.radius[i] - reach);
      EXPECT_LT(s.z[i], spec.height_m - s.radius[i] + reach);
      if (vessel == Vessel::cylinder)
        EXPECT_LT(std::hypot(s.x[i], s.y[i]), 0.5 * spec.width_m - s.radius[i] + reach);
      else
        EXPECT_GT(s.x[i], s.radius[i] - reach);
    }
  }
}

TEST(Genesis3D, TheCacheGivesTheSamePacking) {
  const std::string dir = ::testing::TempDir() + "genesis3d_cache";
  std::filesystem::remove_all(dir);
  const SphereSpecimenSpec spec = small(Vessel::box);
  const SphereSpecimen packed = cached_sphere_specimen(spec, dir);
  const SphereSpecimen loaded = cached_sphere_specimen(spec, dir);
  EXPECT_EQ(packed.x, loaded.x);
  EXPECT_EQ(packed.z, loaded.z);
  EXPECT_EQ(packed.radius, loaded.radius);
  EXPECT_EQ(packed.porosity, loaded.porosity);
  SphereSpecimenSpec other = spec;
  other.seed = 2;
  EXPECT_NE(other.cache_key(), spec.cache_key());
  EXPECT_NE(cached_sphere_specimen(other, dir).x, packed.x);
}

TEST(Genesis3D, BadSpecsAreRefusedNamingTheField) {
  auto message = [](SphereSpecimenSpec spec) {
    try {
      spec.validate();
    } catch (const demcal::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SphereSpecimenSpec spec = small(Vessel::cylinder);
  spec.width_m = 0;
  EXPECT_NE(message(spec).find("diameter_m must be positive"), std::string::npos);
  spec = small(Vessel::box);
  spec.porosity = 0.1;
  EXPECT_NE(message(spec).find("porosity must lie in (0.2, 0.6)"), std::string::npos);
  // More spheres than the machine's memory holds: refused before packing, with the estimate.
  spec = small(Vessel::box);
  spec.width_m = spec.depth_m = 0.1;
  spec.height_m = 0.2;  // about 650k spheres: 1.2 GiB
  try {
    check_packing_memory(spec, 1e9);
    ADD_FAILURE() << "a packing larger than the machine was not refused";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("652943 spheres need about 1.2 GiB to pack, more than this machine's 0.9 GiB allow"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(check_packing_memory(spec, 64e9));
  spec = small(Vessel::box);
  spec.radius_min_m = 1e-5;
  spec.radius_max_m = 1e-5;
  EXPECT_NE(message(spec).find("more than 5 million spheres"), std::string::npos);
}
