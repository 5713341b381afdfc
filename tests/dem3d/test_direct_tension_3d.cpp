// The direct tension test in 3D: a driven (fixed) sphere moves at its own
// velocity whatever its forces and pulls a bonded partner as the closed form
// of a driven spring says; the test pulls the small bonded cylinder apart by
// its grips and breaks it in tension; grips too long for a gauge, a grip
// length that is not positive and a box specimen are refused with the field
// named. Threads, shuffled spheres, exact scaling and the golden are the
// invariant driver's (tests/invariants/lab_tests/direct_tension_3d.json).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/scratch.hpp"
#include "demcal/core/error.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal;
using namespace demcal::dem3d;

namespace {

const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/tension_small_3d.json";

// The small tension scene with `edit` applied (written, "extends" resolved, to the scratch folder).
dem::Scene scene_with(const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = dem::Scene::resolved_json(kScene);
  edit(j);
  const std::string path = test::scratch_path(name + ".json");
  std::ofstream(path) << j.dump(1);
  return dem::Scene::load(path);
}

dem::TestResult run(const dem::Scene& scene) {
  dem::RunOptions o;
  o.seed = 1;
  o.cache_dir = test::scratch_path("cache");
  o.threads = 1;
  return scene.lab_test().run(scene, scene.resolve({}), o);
}

}  // namespace

// Sphere 1 is driven along x at v; sphere 0, free and touching it, is pulled
// by their parallel bond alone (the gap the pull opens keeps the linear
// contact out). Without damping the free sphere lags the driven one by
// (v / omega) sin(omega t), omega = sqrt(k / m), k = kn_b A the bond's axial
// stiffness, so the force on the driven sphere is -k (v / omega) sin(omega t).
TEST(DrivenSpheres3D, ADrivenSpherePullsItsBondedPartnerAsADrivenSpring) {
  constexpr double kRadius = 1e-3, kDensity = 2650, kBondModulus = 2e9, kV = 0.01, kDt = 1e-9;
  WorldSettings settings;
  settings.damping = 0;
  settings.fixed_dt_s = kDt;
  World world(settings);
  const nlohmann::json bond = {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5},
                               {"bond_modulus_pa", kBondModulus}, {"bond_kn_ks", 2.5},
                               {"tensile_strength_pa", 1e12}, {"shear_strength_pa", 1e12}};
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create("parallel_bond", bond, "test")));
  world.spheres.add_sphere({0, 0, 0}, kRadius, kDensity, 0);
  world.spheres.add_sphere({2 * kRadius, 0, 0}, kRadius, kDensity, 0);
  ASSERT_EQ(world.install_bonds(1e-9, 1), 1u);
  const std::size_t driven = world.index_of(1);
  world.spheres.fixed[driven] = 1;
  world.spheres.set_velocity(driven, {kV, 0, 0});

  const double k = kBondModulus / (2 * kRadius) * M_PI * kRadius * kRadius;
  const double m = kDensity * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius, omega = std::sqrt(k / m);
  const int steps = static_cast<int>(0.25 * (2 * M_PI / omega) / kDt);  // a quarter period: the largest pull
  world.run(static_cast<std::uint64_t>(steps));
  const double t = steps * kDt, amplitude = k * kV / omega;

  const std::size_t d = world.index_of(1);
  EXPECT_NEAR(world.spheres.x[d], 2 * kRadius + kV * t, 1e-12 * kRadius) << "it moves at its own velocity";
  EXPECT_EQ(world.spheres.vx[d], kV) << "its velocity is kept, not integrated";
  EXPECT_NEAR(world.contact_force(d).x, -amplitude * std::sin(omega * t), 2e-3 * amplitude);
  EXPECT_NEAR(world.contact_force(world.index_of(0)).x, -world.contact_force(d).x, 1e-12 * amplitude)
      << "the bond pulls its partner with the opposite force";
  EXPECT_GT(world.spheres.vx[world.index_of(0)], 0.0) << "the free sphere follows";
}

TEST(DirectTension3D, PullsTheSmallCylinderApartInTension) {
  const dem::Scene scene = dem::Scene::load(kScene);
  const dem::TestResult r = run(scene);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_EQ(r.ended_by, "stress below stop_fraction_of_peak");
  EXPECT_GT(r.macro.at("sigma_t_direct_MPa"), 0.0);
  EXPECT_GT(r.macro.at("E_tension_GPa"), 0.0);
  // Pulled apart, the bonds break in tension: at most a few in shear.
  EXPECT_GT(r.macro.at("cracks_tension"), 10 * r.macro.at("cracks_shear"));
  // The first curve point, one step into the pull, carries next to nothing; the stress rises with the strain.
  ASSERT_GE(r.curve.size(), 10u);
  EXPECT_LT(std::abs(r.curve.front().stress_pa), 0.02 * r.macro.at("sigma_t_direct_MPa") * 1e6);
  EXPECT_GT(r.curve[3].stress_pa, r.curve[1].stress_pa);
  // The default grips hold two of the largest diameters (4 x 0.9 mm) at each end of the 20 mm cylinder.
  EXPECT_NEAR(r.specimen_info.at("gauge_length_m"), 0.02 - 8 * 9e-4, 2e-4);
  EXPECT_GE(r.specimen_info.at("grip_spheres"), 16.0);
}

TEST(DirectTension3D, RefusesGripsWithoutAGaugeAndGripsOfNoLength) {
  const dem::TestResult r = run(scene_with("long_grips", [](nlohmann::json& j) { j["grips"]["length_m"] = 0.006; }));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("grips.length_m"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("gauge shorter than half"), std::string::npos) << r.reason;
  try {
    scene_with("no_grip", [](nlohmann::json& j) { j["grips"]["length_m"] = -1e-3; });
    FAIL() << "a negative grip length was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("grips.length_m must be positive"), std::string::npos) << e.what();
  }
  try {
    scene_with("box", [](nlohmann::json& j) {
      j["specimen"]["shape"] = "box";
      j["specimen"].erase("diameter_m");
      j["specimen"]["width_m"] = 0.01;
      j["specimen"]["depth_m"] = 0.01;
    });
    FAIL() << "a box specimen was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("specimen.shape"), std::string::npos) << e.what();
  }
}
