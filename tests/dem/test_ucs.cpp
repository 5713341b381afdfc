// The uniaxial compression scene end to end on a small specimen, and the
// evaluation of a curve against hand-computed macro values.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/brazilian_test.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/ucs_test.hpp"

using namespace demcal::dem;

namespace {

std::string scene_path() { return std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json"; }

}  // namespace

TEST(UcsMacroValues, MatchAHandWorkedCurve) {
  // Linear to 20 MPa at 0.1 % strain (E = 20 GPa), nu = 0.25, then softening.
  std::vector<CurvePoint> curve;
  for (int k = 0; k <= 10; ++k) curve.push_back({1e-4 * k, 2e6 * k, 0.25e-4 * k, 0});
  curve.push_back({1.1e-3, 15e6, 5e-4, 10});
  curve.push_back({1.2e-3, 10e6, 9e-4, 20});
  auto m = ucs_macro_values(curve);
  EXPECT_DOUBLE_EQ(m.at("sigma_u_MPa"), 20.0);
  EXPECT_NEAR(m.at("E_GPa"), 20.0, 1e-9);
  EXPECT_NEAR(m.at("E50_GPa"), 20.0, 1e-9);
  EXPECT_NEAR(m.at("nu"), 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(m.at("peak_strain"), 1e-3);
  EXPECT_THROW(ucs_macro_values({curve[0], curve[1]}), demcal::Error);
}

TEST(UcsMacroValues, EAndNuAreTangentsOverTheSameWindow) {
  // sigma = E0 e (1 - e / (2 e_p)) peaks at e_p; eps_lat = a e + b e^2. Least
  // squares over a window centred on a point gives a quadratic's exact
  // derivative there, so E = E0 (1 - e_h / e_p) and nu = a + 2 b e_h at the
  // first point e_h of at least half the peak; the secant nu, a + b e_h, is
  // about 11 % lower here.
  const double E0 = 30e9, e_p = 1e-3, a = 0.1, b = 50.0, de = 1e-5;
  std::vector<CurvePoint> curve;
  for (int k = 0; k <= 130; ++k) {
    const double e = de * k;
    const double stress = k <= 100 ? E0 * e * (1 - e / (2 * e_p)) : E0 * e_p / 2 * (1 - 0.01 * (k - 100));
    curve.push_back({e, stress, a * e + b * e * e, 0});
  }
  std::size_t half = 0;
  while (curve[half].stress_pa < 0.25 * E0 * e_p) ++half;
  const double e_h = curve[half].axial_strain;
  auto m = ucs_macro_values(curve);
  EXPECT_NEAR(m.at("E_GPa"), E0 * (1 - e_h / e_p) / 1e9, 1e-6);
  EXPECT_NEAR(m.at("nu"), a + 2 * b * e_h, 1e-9);
  EXPECT_GT(std::abs(m.at("nu") - (a + b * e_h)), 0.01);  // the secant would not pass
}

TEST(UcsScene, SmallBondedSpecimenGivesPlausibleMacroValues) {
  Scene scene = Scene::load(scene_path());
  RunOptions options;
  options.seed = 1;
  TestResult r = run_ucs(scene, scene.resolve({}), options);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_GT(r.macro.at("sigma_u_MPa"), 1.0);
  EXPECT_LT(r.macro.at("sigma_u_MPa"), 100.0);
  EXPECT_GT(r.macro.at("E_GPa"), 1.0);
  EXPECT_LT(r.macro.at("E_GPa"), 100.0);
  EXPECT_GT(r.macro.at("nu"), 0.0);
  EXPECT_LT(r.macro.at("nu"), 0.5);
  EXPECT_GT(r.macro.at("cracks_tension") + r.macro.at("cracks_shear"), 0.0);
  EXPECT_LT(r.wall_s, 60.0);
  // Stronger bonds make a stronger specimen (same packing, same seed).
  TestResult strong = run_ucs(scene, scene.resolve({{"pb_sigma_c_MPa", 20}, {"pb_tau_c_MPa", 60}}), options);
  ASSERT_TRUE(strong.ok) << strong.reason;
  EXPECT_GT(strong.macro.at("sigma_u_MPa"), 1.3 * r.macro.at("sigma_u_MPa"));
  // Same inputs and seed: the same numbers, bit for bit.
  TestResult again = run_ucs(scene, scene.resolve({}), options);
  EXPECT_EQ(again.macro.at("sigma_u_MPa"), r.macro.at("sigma_u_MPa"));
  EXPECT_EQ(again.macro.at("E_GPa"), r.macro.at("E_GPa"));
}

TEST(UcsScene, BadParametersAreErrorsThatNameThem) {
  Scene scene = Scene::load(scene_path());
  EXPECT_THROW(scene.resolve({{"Ec", 10}}), demcal::Error);
  EXPECT_THROW(scene.resolve({{"Ec_GPa", std::nan("")}}), demcal::Error);
  EXPECT_THROW(scene.resolve({{"Ec_GPa", 1000}}), demcal::Error);  // above the scene's high
  try {
    scene.resolve({{"kn_ks", -1}});
    FAIL();
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("kn_ks = -1 lies outside [0.1, 20]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Scene::load("/nonexistent/scene.json"), demcal::Error);
}

TEST(BrazilianScene, SmallDiscSplitsAtAPlausibleTensileStrength) {
  Scene scene = Scene::load(std::string(DEMCAL_SOURCE_DIR) + "/tests/data/brazilian_small.json");
  RunOptions options;
  TestResult r = run_test(scene, scene.resolve({}), options);
  ASSERT_TRUE(r.ok) << r.reason;
  // Tensile strength: below the UCS of the same material, of the order of the bond strength.
  Scene ucs = Scene::load(scene_path());
  TestResult compression = run_test(ucs, ucs.resolve({}), options);
  ASSERT_TRUE(compression.ok);
  EXPECT_GT(r.macro.at("sigma_t_MPa"), 0.3);
  EXPECT_LT(r.macro.at("sigma_t_MPa"), 0.5 * compression.macro.at("sigma_u_MPa"));
  EXPECT_GT(r.macro.at("cracks_tension"), 0.0);
  // sigma_t scales with the bond strengths.
  TestResult strong = run_test(scene, scene.resolve({{"pb_sigma_c_MPa", 20}, {"pb_tau_c_MPa", 60}}), options);
  ASSERT_TRUE(strong.ok);
  EXPECT_GT(strong.macro.at("sigma_t_MPa"), 1.3 * r.macro.at("sigma_t_MPa"));
}

TEST(UcsScene, AStrongBrittleSpecimenThatBurstsAfterItsPeakIsAResultNotAFailure) {
  // Strong contact bonds store so much strain energy that failure throws disks
  // off at more than 1000 x the platen speed (50 m/s); past the peak that ends
  // the test with the peak values, as a laboratory burst does.
  Scene scene = Scene::load(std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_rock_cb_small.json");
  RunOptions options;
  options.seed = 1;
  TestResult r = run_ucs(scene,
                         scene.resolve({{"Ec_Pa", 29.7e9}, {"cb_sigma_c_mean_Pa", 230e6}, {"cb_tau_c_mean_Pa", 317e6}, {"mu", 0.94}}),
                         options);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_EQ(r.ended_by.rfind("burst after the peak (a disk moves faster than 1000 x the platen speed", 0), 0u) << r.ended_by;
  double peak = 0;
  for (const CurvePoint& p : r.curve) peak = std::max(peak, p.stress_pa);
  EXPECT_DOUBLE_EQ(r.macro.at("sigma_u_MPa"), peak / 1e6);
  EXPECT_LT(r.curve.back().stress_pa, peak);
  EXPECT_GT(r.macro.at("E_GPa"), 1.0);

  // The default (weaker) sandstone ends the ordinary way.
  TestResult normal = run_ucs(scene, scene.resolve({}), options);
  ASSERT_TRUE(normal.ok) << normal.reason;
  EXPECT_EQ(normal.ended_by, "stress below stop_fraction_of_peak");
}
