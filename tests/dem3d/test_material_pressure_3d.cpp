// PFC3D's material pressure (a locked-in isotropic stress by servo walls):
// every wall of the vessel holds the stress, in either direction and in a
// box as in a cylinder; the bonded specimen, relaxed out of its vessel,
// expands by the strain elasticity gives for that stress; a test on it
// reports the stress and gives the same bits on any thread count, in any
// sphere order and under exact scaling; no stress leaves the cached packing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "../common/scratch.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/material_pressure.hpp"
#include "demcal/dem3d/sphere_scene.hpp"

using namespace demcal;
using namespace demcal::dem3d;

namespace {

const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small_3d.json";

// The small UCS scene with `edit` applied (written to the scratch folder).
dem::Scene scene_with(const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = nlohmann::json::parse(std::ifstream(kScene));
  edit(j);
  const std::string path = test::scratch_path(name + ".json");
  std::ofstream(path) << j.dump(1);
  return dem::Scene::load(path);
}

dem::Scene pressured_scene(double stress_pa) {
  return scene_with("pressured_" + std::to_string(stress_pa),
                    [&](nlohmann::json& j) { j["specimen"]["locked_in_stress_pa"] = stress_pa; });
}

dem::RunOptions options(int threads = 1) {
  dem::RunOptions o;
  o.seed = 1;
  o.cache_dir = test::scratch_path("cache");
  o.threads = threads;
  o.min_disks_per_thread = 1;
  return o;
}

double solid_volume(const SphereSpecimen& s) {
  double v = 0;
  for (double r : s.radius) v += 4.0 / 3.0 * M_PI * r * r * r;
  return v;
}

// Every sphere inside the vessel, allowing the overlap a wall's contact takes.
void expect_inside_vessel(const SphereSpecimen& s, double overlap_over_radius = 0.01) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double r = s.radius[i], slack = overlap_over_radius * r;
    EXPECT_GE(s.z[i] - r, -slack) << i;
    EXPECT_LE(s.z[i] + r, s.height_m + slack) << i;
    if (s.vessel == Vessel::cylinder) {
      EXPECT_LE(std::hypot(s.x[i], s.y[i]) + r, 0.5 * s.width_m + slack) << i;
    } else {
      EXPECT_GE(s.x[i] - r, -slack) << i;
      EXPECT_LE(s.x[i] + r, s.width_m + slack) << i;
      EXPECT_GE(s.y[i] - r, -slack) << i;
      EXPECT_LE(s.y[i] + r, s.depth_m + slack) << i;
    }
  }
}

}  // namespace

TEST(MaterialPressure3D, EveryWallHoldsTheStressAndTheSpecimenStaysInItsVessel) {
  const dem::Scene scene = pressured_scene(1e6);
  const auto parameters = scene.resolve({});
  const SphereSpecimen packed = cached_sphere_specimen(sphere_specimen_spec(scene, parameters, 1), options().cache_dir);
  std::map<std::string, double> info;
  const PressuredSpecimen p = install_material_pressure(scene, parameters, packed, 1e6, options(), info);
  ASSERT_EQ(p.reason, "");
  EXPECT_NEAR(p.specimen.locked_in_stress_pa, 1e6, 0.01e6);  // each wall within 1 %, so their mean
  // At 16 GPa the packing's overlaps (made at 1 GPa) hold far more than 1 MPa: the walls moved out.
  EXPECT_GT(p.specimen.porosity, packed.porosity + 0.005);
  const double volume = 0.25 * M_PI * p.specimen.width_m * p.specimen.width_m * p.specimen.height_m;
  EXPECT_NEAR(p.specimen.porosity, 1 - solid_volume(p.specimen) / volume, 1e-12);
  EXPECT_NEAR(info.at("material_pressure_porosity_change"), p.specimen.porosity - packed.porosity, 1e-15);
  EXPECT_GT(info.at("material_pressure_steps"), 0);
  ASSERT_EQ(p.specimen.size(), packed.size());
  expect_inside_vessel(p.specimen);
}

TEST(MaterialPressure3D, SoftContactsUnderTheStressCloseTheVessel) {
  // At 0.1 GPa the packing holds less than 5 MPa: the walls move in and the porosity falls.
  const dem::Scene scene = pressured_scene(5e6);
  const auto parameters = scene.resolve({{"Ec_GPa", 0.1}});
  const SphereSpecimen packed = cached_sphere_specimen(sphere_specimen_spec(scene, parameters, 1), options().cache_dir);
  std::map<std::string, double> info;
  const PressuredSpecimen p = install_material_pressure(scene, parameters, packed, 5e6, options(), info);
  ASSERT_EQ(p.reason, "");
  EXPECT_NEAR(p.specimen.locked_in_stress_pa, 5e6, 0.05e6);
  EXPECT_LT(p.specimen.porosity, packed.porosity - 0.005);
  expect_inside_vessel(p.specimen, 0.25);  // 5 MPa at 0.1 GPa: spheres pressed into the walls by up to a fifth of a radius
}

TEST(MaterialPressure3D, ABoxVesselHoldsItOnSixWalls) {
  const dem::Scene scene = pressured_scene(1e6);
  const auto parameters = scene.resolve({});
  SphereSpecimenSpec spec = sphere_specimen_spec(scene, parameters, 1);
  spec.vessel = Vessel::box;
  spec.width_m = spec.depth_m = 0.009;
  spec.height_m = 0.018;
  const SphereSpecimen packed = cached_sphere_specimen(spec, options().cache_dir);
  std::map<std::string, double> info;
  const PressuredSpecimen p = install_material_pressure(scene, parameters, packed, 1e6, options(), info);
  ASSERT_EQ(p.reason, "");
  EXPECT_NEAR(p.specimen.locked_in_stress_pa, 1e6, 0.01e6);
  EXPECT_GT(p.specimen.width_m, spec.width_m);
  EXPECT_GT(p.specimen.depth_m, spec.depth_m);
  EXPECT_GT(p.specimen.height_m, spec.height_m);
  const double volume = p.specimen.width_m * p.specimen.depth_m * p.specimen.height_m;
  EXPECT_NEAR(p.specimen.porosity, 1 - solid_volume(p.specimen) / volume, 1e-12);
  expect_inside_vessel(p.specimen);
}

TEST(MaterialPressure3D, NoStressLeavesTheCachedPacking) {
  const dem::Scene scene = dem::Scene::load(kScene);
  const auto parameters = scene.resolve({});
  dem::TestResult result;
  SphereSpecimen specimen;
  ASSERT_TRUE(test_specimen(scene, parameters, options(), result, specimen)) << result.reason;
  const SphereSpecimen packed = cached_sphere_specimen(sphere_specimen_spec(scene, parameters, 1), options().cache_dir);
  EXPECT_TRUE(result.specimen_info.empty());
  EXPECT_EQ(specimen.locked_in_stress_pa, 0.0);
  EXPECT_EQ(specimen.x, packed.x);
  EXPECT_EQ(specimen.z, packed.z);
  EXPECT_EQ(specimen.porosity, packed.porosity);
}

// Out of its vessel a contact-bonded specimen is a linear body unloaded from
// the isotropic stress sigma_0 (bonds installed on the compressed contacts,
// which stay linear in tension while bonded): its height grows by sigma_0
// (1 - 2 nu) / E, E and nu its own, measured by compressing the same
// specimen: measured 9.2e-5 axially and 9.7e-5 radially against 8.5e-5.
// 15 %: the 510-sphere specimen's E and nu are loading tangents at half the
// peak. (A parallel bond's linear part stops pulling where a contact
// opens, and at any sigma_0 the expansion is of the order of the weaker
// contacts' overlaps, both being sigma_0 / E: it expands more.)
TEST(MaterialPressure3D, TheRelaxedSpecimenExpandsAsElasticityGives) {
  const double stress_pa = 1e6;
  const dem::Scene scene = scene_with("contact_bonded", [&](nlohmann::json& j) {
    j["specimen"]["locked_in_stress_pa"] = stress_pa;
    j["contacts"]["particle-particle"] = {
        {"model", "contact_bond"},
        {"parameters", {{"modulus_pa", "Ec_GPa*1e9"}, {"kn_ks", "kn_ks"}, {"friction", "mu"},
                        {"tensile_strength_pa", "pb_sigma_c_MPa*1e6"}, {"shear_strength_pa", "pb_tau_c_MPa*1e6"}}}};
  });
  const auto parameters = scene.resolve({{"pb_sigma_c_MPa", 100}, {"pb_tau_c_MPa", 100}});
  dem::TestResult prepared;
  SphereSpecimen pressured;
  ASSERT_TRUE(test_specimen(scene, parameters, options(), prepared, pressured)) << prepared.reason;
  std::map<std::string, double>& info = prepared.specimen_info;
  World world = specimen_world(scene, parameters, pressured, options());
  world.walls = {make_plane({0, 0, 0}, {0, 0, 1}, kPlatenGroup),
                 make_plane({0, 0, pressured.height_m}, {0, 0, -1}, kPlatenGroup)};
  ASSERT_EQ(bond_specimen(world, scene, pressured, 1, info), "");
  EXPECT_EQ(info.at("locked_in_relaxation_breaks"), 0);
  // Least-squares strains of every sphere's displacement (axial about mid-height, radial from the axis); the
  // walls set back on the relaxed specimen would add the spring-back of the spheres that pressed on them.
  double z_du = 0, z_z = 0, r_du = 0, r_r = 0;
  for (std::size_t i = 0; i < world.spheres.size(); ++i) {
    const std::size_t k = world.spheres.id[i];
    const double z0 = pressured.z[k] - 0.5 * pressured.height_m, r0 = std::hypot(pressured.x[k], pressured.y[k]);
    z_du += z0 * (world.spheres.z[i] - pressured.z[k]), z_z += z0 * z0;
    r_du += r0 * (std::hypot(world.spheres.x[i], world.spheres.y[i]) - r0), r_r += r0 * r0;
  }
  const double axial = z_du / z_z, radial = r_du / r_r;

  const dem::TestResult ucs = dem::run_test(scene, parameters, options());
  ASSERT_TRUE(ucs.ok) << ucs.reason;
  const double E_pa = ucs.macro.at("E_GPa") * 1e9, nu = ucs.macro.at("nu");
  const double expected = stress_pa * (1 - 2 * nu) / E_pa;
  EXPECT_NEAR(axial, expected, 0.15 * expected) << "E " << E_pa << " nu " << nu;
  EXPECT_NEAR(radial, expected, 0.15 * expected) << "E " << E_pa << " nu " << nu;
}

TEST(MaterialPressure3D, ATestReportsTheStressAndGivesTheSameBitsOnTwoThreadsAndShuffled) {
  const dem::Scene scene = pressured_scene(1e6);
  const auto parameters = scene.resolve({});
  const dem::TestResult one = dem::run_test(scene, parameters, options(1));
  ASSERT_TRUE(one.ok) << one.reason;
  EXPECT_NEAR(one.specimen_info.at("locked_in_stress_MPa"), 1.0, 0.01);
  EXPECT_GT(one.specimen_info.at("bonds_per_sphere"), 4.0);
  EXPECT_GT(one.porosity, 0.4 + 0.005);  // the scene's packing asks 0.40; the stress opened it
  dem::RunOptions shuffled = options(1);
  shuffled.particle_order_seed = 7;
  for (const dem::RunOptions& o : {options(2), shuffled}) {
    const dem::TestResult other = dem::run_test(scene, parameters, o);
    ASSERT_TRUE(other.ok) << other.reason;
    EXPECT_EQ(other.steps, one.steps);
    for (const auto& [name, value] : one.macro) EXPECT_EQ(other.macro.at(name), value) << name;
    EXPECT_EQ(other.specimen_info, one.specimen_info);
  }
}

// Stresses x 4 (moduli, strengths, the locked-in stress) and the platen speed
// x 2: the same run in half the time, stress outputs x 4 to the bit.
TEST(MaterialPressure3D, ScalesExactly) {
  const dem::Scene scene = pressured_scene(1e6);
  const dem::Scene scaled = scene_with("pressured_scaled", [](nlohmann::json& j) {
    j["specimen"]["locked_in_stress_pa"] = 4e6;
    j["loading"]["platen_velocity_m_s"] = 2 * j["loading"]["platen_velocity_m_s"].get<double>();
  });
  const dem::TestResult a = dem::run_test(scene, scene.resolve({}), options());
  const dem::TestResult b = dem::run_test(
      scaled, scaled.resolve({{"Ec_GPa", 64}, {"pb_sigma_c_MPa", 40}, {"pb_tau_c_MPa", 120}}), options());
  ASSERT_TRUE(a.ok && b.ok) << a.reason << b.reason;
  EXPECT_EQ(a.steps, b.steps);
  for (const char* stress : {"sigma_u_MPa", "E_GPa", "E50_GPa"}) EXPECT_EQ(b.macro.at(stress), 4 * a.macro.at(stress));
  for (const char* ratio : {"nu", "peak_strain", "cracks_tension"}) EXPECT_EQ(b.macro.at(ratio), a.macro.at(ratio));
  EXPECT_EQ(b.specimen_info.at("locked_in_stress_MPa"), 4 * a.specimen_info.at("locked_in_stress_MPa"));
  EXPECT_EQ(b.specimen_info.at("material_pressure_steps"), a.specimen_info.at("material_pressure_steps"));
}
