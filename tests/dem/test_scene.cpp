// Scenes as the one source of truth for parameters: units, variants by
// "extends" (JSON Merge Patch), the fingerprint of what changes results, a
// space that must narrow the scene, and lab tests that report what they declare.
#include <gtest/gtest.h>

#include "../common/error_of.hpp"

#include "../common/scratch.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/describe.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/scene_set.hpp"

using namespace demcal;
using namespace demcal::dem;
using json = nlohmann::json;

using demcal::test::error_of;

namespace {

std::string source(const std::string& relative) { return std::string(DEMCAL_SOURCE_DIR) + "/" + relative; }

json small_scene() {
  std::ifstream in(source("tests/data/ucs_small.json"));
  return json::parse(in);
}

std::string write(const std::string& name, const json& content) {
  const std::string path = demcal::test::scratch_path(name);
  std::ofstream(path) << content.dump(1);
  return path;
}


}  // namespace

TEST(Scene, EveryParameterDeclaresAKnownUnitThatSaysWhatItIs) {
  Scene scene = Scene::from_json(small_scene(), "small");
  EXPECT_EQ(scene.parameters().at("Ec_GPa").quantity, Quantity::Stress);
  EXPECT_EQ(scene.parameters().at("kn_ks").quantity, Quantity::Dimensionless);
  EXPECT_TRUE(is_stress_like(scene.parameters().at("pb_sigma_c_MPa").quantity));
  EXPECT_FALSE(is_stress_like(scene.parameters().at("mu").quantity));

  json missing = small_scene();
  missing["parameters"]["mu"].erase("unit");
  EXPECT_NE(error_of([&] { Scene::from_json(missing, "s.json"); }).find("s.json: parameters.mu: missing \"unit\""),
            std::string::npos);
  json unknown = small_scene();
  unknown["parameters"]["Ec_GPa"]["unit"] = "psi";
  EXPECT_NE(error_of([&] { Scene::from_json(unknown, "s.json"); }).find("unknown unit \"psi\""), std::string::npos);
}

TEST(Scene, ExtendsAppliesAMergePatchToItsBaseAlongAChain) {
  const std::string base = write("base.json", small_scene());
  const std::string base_name = base.substr(base.find_last_of('/') + 1);
  // Child: a new default, a wider specimen, a parameter's note removed by null.
  json child = {{"extends", base_name},
                {"name", "child"},
                {"specimen", {{"width_m", 0.012}}},
                {"parameters", {{"mu", {{"value", 0.3}}}}}};
  const std::string child_path = write("child.json", child);
  json grandchild = {{"extends", child_path.substr(child_path.find_last_of('/') + 1)},
                     {"loading", {{"platen_velocity_m_s", 0.04}}}};
  const std::string grandchild_path = write("grandchild.json", grandchild);

  Scene scene = Scene::load(grandchild_path);
  EXPECT_EQ(scene.name(), "child");
  EXPECT_DOUBLE_EQ(scene.parameters().at("mu").value, 0.3);
  EXPECT_EQ(scene.parameters().at("mu").unit, "1");  // merged, not replaced
  EXPECT_DOUBLE_EQ(scene.parameters().at("Ec_GPa").value, 16);
  EXPECT_DOUBLE_EQ(scene.loading().platen_velocity_m_s, 0.04);
  EXPECT_DOUBLE_EQ(specimen_spec(scene, scene.resolve({}), 1).width_m, 0.012);
  EXPECT_DOUBLE_EQ(specimen_spec(scene, scene.resolve({}), 1).height_m, 0.02);

  // null deletes: a parameter removed by the patch, whose contacts still use it, fails to load.
  json removes = {{"extends", base_name}, {"parameters", {{"mu", nullptr}}}};
  EXPECT_NE(error_of([&] { Scene::load(write("removes.json", removes)); }).find("\"mu\""), std::string::npos);

  json cycle = {{"extends", "cycle.json"}};
  const std::string cycle_path = write("cycle.json", cycle);
  const std::string e = error_of([&] { Scene::load(cycle_path); });
  EXPECT_EQ(e.rfind(cycle_path + ": ", 0), 0u) << e;  // names the file given
  EXPECT_NE(e.find("(a cycle)"), std::string::npos) << e;
  json missing_base = {{"extends", "no_such_scene.json"}};
  EXPECT_NE(error_of([&] { Scene::load(write("orphan.json", missing_base)); }).find("cannot open"), std::string::npos);
}

TEST(Scene, ShippedVariantsEqualTheirBaseExceptWhatTheyChange) {
  json base = Scene::resolved_json(source("data/scenes/ucs_concrete.json"));
  json demo = Scene::resolved_json(source("data/scenes/ucs_concrete_demo.json"));
  EXPECT_EQ(demo["contacts"], base["contacts"]);
  EXPECT_EQ(demo["parameters"], base["parameters"]);
  EXPECT_EQ(demo["aggregates"], base["aggregates"]);
  EXPECT_DOUBLE_EQ(demo["specimen"]["radius_min_m"].get<double>(), 0.0008);
  EXPECT_EQ(demo["specimen"]["porosity"], base["specimen"]["porosity"]);
}

TEST(Scene, ElasticSpeedupIsCheckedAndOnlyForTheUcs) {
  const json ucs = Scene::resolved_json(source("data/scenes/ucs_rock_pb.json"));
  EXPECT_EQ(Scene::from_json(ucs, "u.json").loading().elastic_speedup, 1.0);  // one speed unless asked
  json fast = ucs;
  fast["loading"]["elastic_speedup"] = 4;
  fast["loading"]["speedup_until_utilisation"] = 0.4;
  const Scene quick = Scene::from_json(fast, "u.json");
  EXPECT_EQ(quick.loading().elastic_speedup, 4.0);
  EXPECT_EQ(quick.loading().speedup_until_utilisation, 0.4);
  EXPECT_NE(quick.fingerprint(), Scene::from_json(ucs, "u.json").fingerprint());
  json bad = fast;
  bad["loading"]["elastic_speedup"] = 0.5;
  EXPECT_NE(error_of([&] { Scene::from_json(bad, "u.json"); })
                .find("u.json: loading: elastic_speedup must lie in [1, 20] (1: one platen speed throughout)"),
            std::string::npos);
  bad = fast;
  bad["loading"]["platen_velocity_m_s"] = 1;
  bad["loading"]["elastic_speedup"] = 15;
  EXPECT_NE(error_of([&] { Scene::from_json(bad, "u.json"); })
                .find("u.json: loading: elastic_speedup x platen_velocity_m_s must be at most 10 m/s"),
            std::string::npos);
  bad = fast;
  bad["loading"]["speedup_until_utilisation"] = 1;
  EXPECT_NE(error_of([&] { Scene::from_json(bad, "u.json"); })
                .find("u.json: loading: speedup_until_utilisation must lie in (0, 1)"),
            std::string::npos);
  json disc = Scene::resolved_json(source("data/scenes/brazilian_rock_pb.json"));
  disc["loading"]["elastic_speedup"] = 2;
  EXPECT_NE(error_of([&] { Scene::from_json(disc, "b.json"); })
                .find("b.json: loading: elastic_speedup: only uniaxial compression uses it (this scene's test is brazilian)"),
            std::string::npos);
}

TEST(Scene, AggregateFillAndPlatenStartAreCheckedChoices) {
  json shipped = Scene::resolved_json(source("data/scenes/ucs_concrete.json"));
  EXPECT_EQ(scene_aggregates(Scene::from_json(shipped, "c.json"))->fill, demcal::dem::AggregateFill::count);  // as Su et al.
  json concrete = shipped;
  concrete["aggregates"].erase("fill");
  EXPECT_EQ(scene_aggregates(Scene::from_json(concrete, "c.json"))->fill, demcal::dem::AggregateFill::area);  // the default
  json count = concrete;
  count["aggregates"]["fill"] = "count";
  const Scene counted = Scene::from_json(count, "c.json");
  EXPECT_EQ(scene_aggregates(counted)->fill, demcal::dem::AggregateFill::count);
  EXPECT_NE(counted.fingerprint(), Scene::from_json(concrete, "c.json").fingerprint());
  json outer = concrete;
  outer["loading"]["platen_start"] = "outermost_disks";
  EXPECT_EQ(Scene::from_json(outer, "c.json").loading().platen_start,
            demcal::dem::LoadingSpec::PlatenStart::outermost_disks);
  EXPECT_EQ(Scene::from_json(concrete, "c.json").loading().platen_start,
            demcal::dem::LoadingSpec::PlatenStart::vessel_faces);  // the default, as PFC
  outer["loading"]["platen_start"] = "top";
  EXPECT_NE(error_of([&] { Scene::from_json(outer, "c.json"); })
                .find("c.json: loading: \"platen_start\" must be \"vessel_faces\" or \"outermost_disks\" (got \"top\")"),
            std::string::npos);
  json damping = concrete;
  damping["loading"]["local_damping"] = 1.2;
  EXPECT_NE(error_of([&] { Scene::from_json(damping, "c.json"); }).find("c.json: loading: local_damping must lie in [0, 1)"),
            std::string::npos);
  damping["loading"]["local_damping"] = 0.3;
  EXPECT_EQ(Scene::from_json(damping, "c.json").loading().local_damping, 0.3);
  EXPECT_EQ(Scene::from_json(concrete, "c.json").loading().local_damping, 0.7);
  EXPECT_NE(Scene::from_json(damping, "c.json").fingerprint(), Scene::from_json(concrete, "c.json").fingerprint());
  count["aggregates"]["fill"] = "volume";
  EXPECT_NE(error_of([&] { Scene::from_json(count, "c.json"); })
                .find("c.json: aggregates: \"fill\" must be \"area\" or \"count\" (got \"volume\")"),
            std::string::npos);
}

TEST(Scene, FingerprintCoversPhysicsNotDescriptionsNotesOrBounds) {
  const std::string original = Scene::from_json(small_scene(), "a").fingerprint();
  json cosmetic = small_scene();
  cosmetic["name"] = "renamed";
  cosmetic["description"] = "another description";
  cosmetic["parameters"]["Ec_GPa"]["note"] = "a note";
  cosmetic["parameters"]["Ec_GPa"]["high"] = 400;
  cosmetic["parameters"]["Ec_GPa"]["unit"] = "GPa";
  EXPECT_EQ(Scene::from_json(cosmetic, "b").fingerprint(), original);

  json new_default = small_scene();
  new_default["parameters"]["Ec_GPa"]["value"] = 17;
  EXPECT_NE(Scene::from_json(new_default, "c").fingerprint(), original);
  json new_loading = small_scene();
  new_loading["loading"]["platen_velocity_m_s"] = 0.04;
  EXPECT_NE(Scene::from_json(new_loading, "d").fingerprint(), original);
  json new_specimen = small_scene();
  new_specimen["specimen"]["porosity"] = 0.15;
  EXPECT_NE(Scene::from_json(new_specimen, "e").fingerprint(), original);
}

TEST(Scene, ASpaceMustNarrowTheScene) {
  Scene scene = Scene::from_json(small_scene(), "scene.json");
  auto space = [](const std::string& text) { return ParameterSpace::from_json(json::parse(text), "space.json"); };
  EXPECT_NO_THROW(scene.check_space(space(R"({"parameters": [{"name": "Ec_GPa", "unit": "GPa", "low": 5, "high": 40}]})"),
                                    "space.json"));
  std::string e = error_of([&] {
    scene.check_space(space(R"({"parameters": [{"name": "porosity_x", "low": 0.1, "high": 0.2}]})"), "space.json");
  });
  EXPECT_NE(e.find("space.json: parameter \"porosity_x\" is not a parameter of the scene scene.json"), std::string::npos)
      << e;
  e = error_of([&] { scene.check_space(space(R"({"parameters": [{"name": "mu", "low": 0.1, "high": 20}]})"), "space.json"); });
  EXPECT_NE(e.find("space.json: mu high 20 lies outside the bounds [0, 10] the scene scene.json declares"),
            std::string::npos)
      << e;
  e = error_of([&] {
    scene.check_space(space(R"({"parameters": [{"name": "Ec_GPa", "unit": "MPa", "low": 5, "high": 40}]})"), "space.json");
  });
  EXPECT_NE(e.find("has unit \"MPa\" but the scene scene.json declares \"GPa\""), std::string::npos) << e;
  e = error_of([&] {
    scene.check_space(space(R"({"parameters": [{"name": "Ec_GPa", "low": 5, "high": 40}], "fixed": {"Ec_X": 3}})"),
                      "space.json");
  });
  EXPECT_NE(e.find("fixed parameter \"Ec_X\""), std::string::npos) << e;
}

TEST(Scene, TestsAndContactRolesComeFromTheRegistries) {
  json unknown_test = small_scene();
  unknown_test["test"] = "triaxial_3d";
  std::string e = error_of([&] { Scene::from_json(unknown_test, "s.json"); });
  EXPECT_NE(e.find("\"test\" must be one of \"ucs\", \"brazilian\", \"biaxial\", \"external\", \"heap\", \"wave_strip\", \"slope\", \"ucs_3d\", \"brazilian_3d\", \"triaxial\", \"heap_3d\", \"drum_3d\", \"baffle_lift_3d\", \"direct_tension_3d\" (got \"triaxial_3d\")"), std::string::npos) << e;

  json extra_role = small_scene();
  extra_role["contacts"]["disk-wall"] = extra_role["contacts"]["particle-platen"];
  e = error_of([&] { Scene::from_json(extra_role, "s.json"); });
  EXPECT_NE(e.find("unknown contact role \"disk-wall\" (this scene's roles: particle-particle, particle-platen)"),
            std::string::npos)
      << e;

  json bad_model_parameter = small_scene();
  bad_model_parameter["contacts"]["particle-particle"]["parameters"]["tensile_strenght_pa"] = 1;
  e = error_of([&] { Scene::from_json(bad_model_parameter, "s.json"); });
  EXPECT_NE(e.find("s.json: contacts.particle-particle"), std::string::npos) << e;

  Scene scene = Scene::from_json(small_scene(), "s");
  ASSERT_EQ(scene.contact_roles().size(), 2u);
  EXPECT_EQ(scene.contact_roles()[0].name, "particle-particle");
  EXPECT_EQ(scene.contact_roles()[1].name, "particle-platen");
}

// The roles' names from before 3D ("disk-disk", "disk-platen", "disk-wall")
// still read, as the same roles: the same contacts and the same fingerprint
// (stored results stay valid whichever spelling a file uses).
TEST(Scene, OldRoleNamesReadAsTheDimensionNeutralOnes) {
  json new_names = small_scene();
  ASSERT_TRUE(new_names["contacts"].contains("particle-particle"));
  json old_names = new_names;
  old_names["contacts"] = {{"disk-disk", new_names["contacts"]["particle-particle"]},
                           {"disk-platen", new_names["contacts"]["particle-platen"]}};
  const Scene a = Scene::from_json(old_names, "old.json"), b = Scene::from_json(new_names, "new.json");
  EXPECT_EQ(a.contacts().at("particle-particle").model, b.contacts().at("particle-particle").model);
  EXPECT_EQ(a.contacts().at("particle-platen").parameters, b.contacts().at("particle-platen").parameters);
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  json both = old_names;
  both["contacts"]["particle-particle"] = both["contacts"]["disk-disk"];
  const std::string e = error_of([&] { Scene::from_json(both, "both.json"); });
  EXPECT_NE(e.find("both.json: contacts: \"disk-disk\" and \"particle-particle\" name the same role (particle-particle); "
                   "keep one"),
            std::string::npos)
      << e;
  // A bad parameter is named under the spelling the file uses.
  old_names["contacts"]["disk-disk"]["parameters"]["tensile_strenght_pa"] = 1;
  EXPECT_NE(error_of([&] { Scene::from_json(old_names, "old.json"); }).find("old.json: contacts.disk-disk"),
            std::string::npos);
}

// Each test names its engine; describe says it, and lists the contact models per engine.
TEST(Scene, DescribeSaysTheDimensionOfEachTest) {
  EXPECT_EQ(describe_scene(Scene::from_json(small_scene(), "s.json"))["dimension"], 2);
  json registries = describe_registries();
  EXPECT_EQ(registries["test_dimensions"]["ucs"], 2);
  EXPECT_EQ(registries["test_dimensions"]["heap"], 2);
  EXPECT_TRUE(registries["test_dimensions"]["external"].is_null());  // its own program decides
  EXPECT_EQ(registries["contact_model_parameters"]["2d"]["linear"],
            json({"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction"}));
}

TEST(LabTests, ARunReportsExactlyTheOutputsItsTestDeclares) {
  for (const char* file : {"tests/data/ucs_small.json", "tests/data/brazilian_small.json"}) {
    Scene scene = Scene::load(source(file));
    RunOptions options;
    TestResult r = run_test(scene, scene.resolve({}), options);
    ASSERT_TRUE(r.ok) << file << ": " << r.reason;
    std::set<std::string> always, reported;
    for (const OutputSpec& o : scene.lab_test().outputs(scene))
      if (o.always) always.insert(o.name);
    for (const auto& [name, value] : r.macro)
      if (always.count(name)) reported.insert(name);
    EXPECT_EQ(reported, always) << file;
  }
}

TEST(Scene, FinerDisksDivideTheRadiiNumbersAndExpressions) {
  json numbers = Scene::resolved_json(source("tests/data/ucs_small.json"));
  json fine = Scene::with_finer_disks(numbers, 2.0, "x.json");
  EXPECT_DOUBLE_EQ(fine["specimen"]["radius_min_m"].get<double>(), 1.5e-4);
  EXPECT_DOUBLE_EQ(fine["specimen"]["radius_max_m"].get<double>(), 2.25e-4);
  json expressions = Scene::resolved_json(source("tests/data/ucs_rock_cb_small.json"));
  Scene rock = Scene::from_json(Scene::with_finer_disks(expressions, 2.0, "x.json"), "x.json");
  const SpecimenSpec s = specimen_spec(rock, rock.resolve({}), 1);
  EXPECT_DOUBLE_EQ(s.radius_min_m, 0.00075 * 0.5);
  EXPECT_DOUBLE_EQ(s.radius_max_m, 0.00075 * 1.5 * 0.5);
  EXPECT_THROW(Scene::with_finer_disks(numbers, 0.5, "x.json"), demcal::Error);
}

TEST(LabTests, DescribeListsParametersOutputsAndContacts) {
  Scene scene = Scene::load(source("tests/data/ucs_small.json"));
  json d = describe_scene(scene);
  EXPECT_EQ(d["test"], "ucs");
  EXPECT_EQ(d["parameters"]["Ec_GPa"]["unit"], "GPa");
  EXPECT_EQ(d["parameters"]["Ec_GPa"]["quantity"], "stress");
  EXPECT_EQ(d["parameters"]["Ec_GPa"]["value"], 16.0);
  EXPECT_EQ(d["outputs"]["sigma_u_MPa"]["unit"], "MPa");
  EXPECT_EQ(d["outputs"]["reached_strain_limit"]["optional"], true);
  EXPECT_EQ(d["contacts"]["particle-particle"]["model"], "parallel_bond");
  EXPECT_EQ(d["parameters"]["Ec_GPa"]["shapes_specimen"], false);
  EXPECT_EQ(d["parameters"]["Ec_GPa"]["si_factor"], 1e9);
  EXPECT_EQ(d["outputs"]["sigma_u_MPa"]["stress_like"], true);
  EXPECT_EQ(d["outputs"]["sigma_u_MPa"]["si_factor"], 1e6);
  EXPECT_EQ(d["outputs"]["nu"]["stress_like"], false);
  // Radii given by parameters: each value is another packing.
  json rock = describe_scene(Scene::load(source("tests/data/ucs_rock_cb_small.json")));
  EXPECT_EQ(rock["parameters"]["R_min_m"]["shapes_specimen"], true);
  EXPECT_EQ(rock["parameters"]["R_max_over_R_min"]["shapes_specimen"], true);
  EXPECT_EQ(rock["parameters"]["cb_sigma_c_mean_Pa"]["shapes_specimen"], false);
  json registries = describe_registries();
  EXPECT_EQ(registries["tests"], json({"ucs", "brazilian", "biaxial", "external", "heap", "wave_strip", "slope", "ucs_3d", "brazilian_3d", "triaxial", "heap_3d", "drum_3d", "baffle_lift_3d", "direct_tension_3d"}));
  // Each engine whose tests are registered, with its own models.
  EXPECT_EQ(registries["contact_models"],
            json({{"2d", {"linear", "parallel_bond", "contact_bond", "flat_joint", "hertz_mindlin", "jkr"}},
                  {"3d", {"linear", "hertz_mindlin", "jkr", "sjkr", "contact_bond", "parallel_bond", "flat_joint"}}}));
  EXPECT_EQ(registries["test_dimensions"]["ucs_3d"], 3);
}

// Each output says what values it can take (a target outside is refused
// before any run): [low, high], null for an open end.
TEST(LabTests, DescribeGivesEachOutputItsPhysicalRange) {
  json d = describe_scene(Scene::load(source("tests/data/ucs_small.json")));
  EXPECT_EQ(d["outputs"]["sigma_u_MPa"]["range"], json::parse("[0, null]"));
  EXPECT_EQ(d["outputs"]["nu"]["range"], json::parse("[-1, 1]"));
  EXPECT_EQ(d["outputs"]["reached_strain_limit"]["range"], json::parse("[0, 1]"));
  EXPECT_EQ(d["outputs"]["cracks_shear"]["range"], json::parse("[0, null]"));
  json fake = describe_scene(Scene::load(source("tests/data/external_fake.json")));
  EXPECT_EQ(fake["outputs"]["z"]["range"], json::parse("[null, null]"));  // an external output: any value by default
  // An external scene may state its outputs' ranges.
  json scene = json::parse(std::ifstream(source("tests/data/external_fake.json")));
  scene["outputs"]["y_MPa"]["range"] = json::parse("[0, null]");
  EXPECT_EQ(describe_scene(Scene::from_json(scene, source("tests/data/x.json")))["outputs"]["y_MPa"]["range"],
            json::parse("[0, null]"));
  scene["outputs"]["y_MPa"]["range"] = json::parse("[3, 1]");
  EXPECT_NE(error_of([&] { Scene::from_json(scene, source("tests/data/x.json")); })
                .find("outputs.y_MPa.range: low must be below high"),
            std::string::npos);
}

// What the study layer used to keep lists of comes from describe: each
// test's headline outputs, its moduli ranked (the preferred scale target),
// and its curve's axes.
TEST(LabTests, DescribeFlagsHeadlinesModuliAndTheCurvesAxes) {
  json ucs = describe_scene(Scene::load(source("tests/data/ucs_small.json")));
  EXPECT_EQ(ucs["outputs"]["sigma_u_MPa"].value("headline", false), true);
  EXPECT_EQ(ucs["outputs"]["cracks_shear"].value("headline", false), false);
  EXPECT_EQ(ucs["outputs"]["E_GPa"]["modulus"], 1);
  EXPECT_EQ(ucs["outputs"]["E50_GPa"]["modulus"], 2);
  EXPECT_FALSE(ucs["outputs"]["sigma_u_MPa"].contains("modulus"));
  EXPECT_EQ(ucs["curve_axes"], json({{"x", "axial strain"}, {"y", "axial stress (MPa)"}}));
  json disc = describe_scene(Scene::load(source("tests/data/brazilian_small.json")));
  EXPECT_EQ(disc["curve_axes"]["y"], "2F / (pi D t) (MPa)");
  EXPECT_EQ(disc["outputs"]["sigma_t_MPa"].value("headline", false), true);
  json list = describe_scene_set(SceneSet::load(source("tests/data/tests_small.json")));
  for (const json& t : list["tests"]) EXPECT_TRUE(t.contains("curve_axes")) << t.dump();
  json wave = describe_scene(Scene::load(source("tests/data/wave_strip_small.json")));
  EXPECT_TRUE(wave["curve_axes"].is_null());  // velocity histories, not a stress-strain curve
}

// A confined series says which sigma_3 each piece of its curve was run at, in
// order, so that a lab curve at one confinement can be matched to its piece.
TEST(LabTests, DescribeListsAConfinedSeriesSigma3InTheOrderOfItsCurve) {
  json biaxial = describe_scene(Scene::load(source("data/scenes/biaxial_rock_pb.json")));
  EXPECT_EQ(biaxial["curve_confinements_MPa"], json({1.0, 2.0, 4.0, 8.0}));
  EXPECT_EQ(biaxial["curve_axes"]["y"], "deviatoric stress (MPa)");
  json triaxial = describe_scene(Scene::load(source("data/scenes/triaxial_rock_pb_3d.json")));
  EXPECT_EQ(triaxial["curve_confinements_MPa"], json({1.0, 2.0, 4.0, 8.0}));
  EXPECT_TRUE(describe_scene(Scene::load(source("tests/data/ucs_small.json")))["curve_confinements_MPa"].is_null());
  json list = describe_scene_set(SceneSet::load(source("tests/data/tests_small.json")));
  for (const json& t : list["tests"]) EXPECT_TRUE(t.contains("curve_confinements_MPa")) << t.dump();
}

// The registries list every contact model's parameter keys (the reference
// pages are checked against them) and a key a model does not take is refused
// naming the allowed ones.
TEST(LabTests, RegistriesListEveryModelsParameterKeys) {
  json registries = describe_registries();
  for (const std::string& model : registries["contact_models"]["2d"].get<std::vector<std::string>>())
    EXPECT_FALSE(registries["contact_model_parameters"]["2d"][model].empty()) << model;
  EXPECT_EQ(registries["contact_model_parameters"]["2d"]["linear"],
            json({"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction"}));
  const auto keys = registries["contact_model_parameters"]["2d"]["jkr"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(keys.begin(), keys.end(), "work_of_adhesion_j_m2"), keys.end());
  EXPECT_NE(std::find(keys.begin(), keys.end(), "rolling_friction_epsd"), keys.end());
  EXPECT_EQ(registries["test_descriptions"].size(), registries["tests"].size());
  const std::string e = error_of([] {
    ContactModelRegistry::instance().create("linear", {{"modulus_pa", 1e9}, {"kn_ks", 1.0}, {"friction", 0.5}, {"fric", 1}},
                                            "scene.json: contacts.disk-disk");
  });
  EXPECT_NE(e.find("scene.json: contacts.disk-disk: unknown parameter \"fric\" (allowed: modulus_pa, kn_ks"),
            std::string::npos)
      << e;
}
