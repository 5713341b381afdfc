// A small concrete specimen end to end: aggregates become clumps, the three
// phase contacts are bound, the UCS gives plausible macro values and cracks
// are counted by phase; a scene with aggregates must name the phase contacts.
#include <gtest/gtest.h>

#include "demcal/core/error.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/ucs_test.hpp"

namespace {

using namespace demcal::dem;

std::string small_scene() { return std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_concrete_small.json"; }

TEST(ConcreteUcs, SmallSpecimenGivesPlausibleMacroValues) {
  Scene scene = Scene::load(small_scene());
  ASSERT_TRUE(scene.has_section("aggregates"));
  RunOptions options;
  options.seed = 2;
  TestResult r = run_ucs(scene, scene.resolve({}), options);
  ASSERT_TRUE(r.ok) << r.reason;
  const double sigma_u = r.macro.at("sigma_u_MPa"), E = r.macro.at("E_GPa"), nu = r.macro.at("nu");
  EXPECT_TRUE(std::isfinite(sigma_u) && sigma_u > 1.0) << sigma_u;
  EXPECT_TRUE(std::isfinite(E) && E > 1.0) << E;
  EXPECT_GT(nu, 0.0);
  EXPECT_LT(nu, 0.5);
  // 40 x 80 mm: the polygons fill Walraven's P_c (0.287 over 5-15 mm) within half the largest
  // polygon's area (0.023 of this small section), and all are placed.
  EXPECT_NEAR(r.specimen_info.at("aggregate_area_fraction_target"), 0.287, 0.001);
  EXPECT_NEAR(r.specimen_info.at("aggregate_area_fraction"), r.specimen_info.at("aggregate_area_fraction_target"), 0.03);
  EXPECT_EQ(r.specimen_info.at("aggregates_placed"), r.specimen_info.at("aggregates_requested"));
  EXPECT_EQ(r.specimen_info.at("aggregates_without_disks"), 0.0);
  EXPECT_GT(r.specimen_info.at("aggregate_disks"), 50.0);
  const double phases = r.macro.at("cracks_mortar_tension") + r.macro.at("cracks_mortar_shear") +
                        r.macro.at("cracks_itz_tension") + r.macro.at("cracks_itz_shear");
  EXPECT_EQ(phases, r.macro.at("cracks_tension") + r.macro.at("cracks_shear"));
  EXPECT_GT(r.macro.at("cracks_itz_tension") + r.macro.at("cracks_itz_shear"), 0.0);
}

TEST(ConcreteUcs, StrongerInterfaceGivesAStrongerConcrete) {
  Scene scene = Scene::load(small_scene());
  RunOptions options;
  options.seed = 2;
  TestResult weak = run_ucs(scene, scene.resolve({{"pb_sigma_c_j_MPa", 1}, {"pb_tau_c_j_MPa", 1}}), options);
  TestResult strong = run_ucs(scene, scene.resolve({{"pb_sigma_c_j_MPa", 30}, {"pb_tau_c_j_MPa", 30}}), options);
  ASSERT_TRUE(weak.ok && strong.ok) << weak.reason << strong.reason;
  EXPECT_GT(strong.macro.at("sigma_u_MPa"), 1.1 * weak.macro.at("sigma_u_MPa"));
}

TEST(ConcreteUcs, SceneWithAggregatesMustNameThePhaseContacts) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "name": "x", "test": "ucs",
    "specimen": {"width_m": 0.04, "height_m": 0.08, "porosity": 0.12, "radius_min_m": 5e-4, "radius_max_m": 1e-3, "density_kg_m3": 2000},
    "aggregates": {"size_range_mm": [5, 15]},
    "contacts": {"disk-disk": {"model": "linear", "parameters": {"modulus_pa": 1e9, "kn_ks": 1, "friction": 0}},
                 "disk-platen": {"model": "linear", "parameters": {"modulus_pa": 1e9, "kn_ks": 1, "friction": 0}}}})");
  try {
    Scene::from_json(j, "x.json");
    FAIL() << "expected an error";
  } catch (const demcal::Error& e) {
    // A concrete's roles are its phases' (disk-disk, read as particle-particle, is none of them).
    EXPECT_NE(std::string(e.what()).find("unknown contact role \"disk-disk\" (this scene's roles: mortar-mortar, "
                                         "mortar-aggregate, aggregate-aggregate, particle-platen)"),
              std::string::npos)
        << e.what();
  }
  j["aggregates"]["size_range_mm"] = {15, 5};
  EXPECT_THROW(Scene::from_json(j, "x.json"), demcal::Error);
}

}  // namespace
