// Several lab tests per design point: a test list shares one parameter set,
// names its outputs (prefixed only where two tests clash), runs every test
// with the point's seed, fails the point with the test that failed, and a
// list of one is exactly its scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/scratch.hpp"
#include "demcal/core/error.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/describe.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/result_json.hpp"
#include "demcal/dem/scene_set.hpp"

using namespace demcal::dem;
using json = nlohmann::json;

namespace {

std::string data(const std::string& name) { return std::string(DEMCAL_SOURCE_DIR) + "/tests/data/" + name; }

std::string write(const std::string& name, const json& content) {
  const std::string path = demcal::test::scratch_path(name);
  std::ofstream(path) << content.dump(1);
  return path;
}

std::string error_of(const std::string& path) {
  try {
    SceneSet::load(path);
  } catch (const demcal::Error& e) {
    return e.what();
  }
  return "";
}

bool has(const std::vector<OutputSpec>& outputs, const std::string& name) {
  return std::any_of(outputs.begin(), outputs.end(), [&](const OutputSpec& o) { return o.name == name; });
}

}  // namespace

TEST(SceneSet, OutputsArePrefixedOnlyWhereTestsClash) {
  const SceneSet set = SceneSet::load(data("tests_small.json"));
  ASSERT_EQ(set.size(), 3u);
  EXPECT_EQ(set.label(0), "ucs");
  EXPECT_EQ(set.label(1), "brazilian");
  EXPECT_EQ(set.label(2), "biaxial");
  const std::vector<OutputSpec> outputs = set.outputs();
  for (const char* name : {"sigma_u_MPa", "E_GPa", "nu", "sigma_t_MPa", "q_peak_MPa_1", "c_MPa", "phi_deg",
                           "ucs.cracks_tension", "brazilian.cracks_tension"})
    EXPECT_TRUE(has(outputs, name)) << name;
  // cracks_tension_1 is the biaxial test's alone, so it keeps its name.
  EXPECT_TRUE(has(outputs, "cracks_tension_1"));
  EXPECT_FALSE(has(outputs, "cracks_tension"));
  // One parameter set: the union, here the five names all three scenes share.
  EXPECT_EQ(set.parameters().size(), 5u);
}

TEST(SceneSet, ASetOfOneIsItsScene) {
  const SceneSet set = SceneSet::load(data("ucs_small.json"));
  const Scene scene = Scene::load(data("ucs_small.json"));
  EXPECT_EQ(set.fingerprint(), scene.fingerprint());
  EXPECT_EQ(describe_scene_set(set), describe_scene(scene));
  RunOptions options;
  options.seed = 3;
  const std::map<std::string, double> parameters = scene.resolve({{"pb_sigma_c_MPa", 12}});
  json from_set = set.run(parameters, options);
  const TestResult r = run_test(scene, parameters, options);
  json direct = result_json(r, parameters, 3);
  direct["curve"] = curve_json(r);
  // Same bits but the wall times.
  for (json* j : {&from_set, &direct})
    for (const char* timing : {"wall_s", "test_wall_s", "particle_steps_per_s"}) j->erase(timing);
  EXPECT_EQ(from_set, direct);
}

TEST(SceneSet, AListRunsEveryTestWithThePointsSeed) {
  const SceneSet set = SceneSet::load(data("tests_small.json"));
  RunOptions options;
  options.seed = 2;
  const json r = set.run(set.resolve({}), options);
  ASSERT_EQ(r.at("status"), "ok") << r.at("reason");
  EXPECT_EQ(r.at("test_runs"), 3);
  // Each test as its scene alone gives it, with the same seed.
  const Scene ucs = Scene::load(data("ucs_small.json"));
  const TestResult alone = run_test(ucs, ucs.resolve({}), options);
  EXPECT_EQ(r.at("macro").at("sigma_u_MPa").get<double>(), alone.macro.at("sigma_u_MPa"));
  EXPECT_EQ(r.at("macro").at("ucs.cracks_tension").get<double>(), alone.macro.at("cracks_tension"));
  EXPECT_TRUE(r.at("macro").contains("sigma_t_MPa"));
  EXPECT_TRUE(r.at("macro").contains("phi_deg"));
  EXPECT_EQ(r.at("tests").at("ucs").at("particles"), alone.particles);
  // Each test's curve under its label, and the cost summed.
  EXPECT_TRUE(r.at("curve").contains("ucs.stress_MPa"));
  EXPECT_TRUE(r.at("curve").contains("biaxial.confining_stress_MPa"));
  const std::uint64_t steps = r.at("tests").at("ucs").at("steps").get<std::uint64_t>() +
                              r.at("tests").at("brazilian").at("steps").get<std::uint64_t>() +
                              r.at("tests").at("biaxial").at("steps").get<std::uint64_t>();
  EXPECT_EQ(r.at("steps").get<std::uint64_t>(), steps);
}

TEST(SceneSet, AFailedTestFailsThePointWithItsLabel) {
  json brazilian = Scene::resolved_json(data("brazilian_small.json"));
  brazilian["loading"]["max_wall_s"] = 1e-9;  // times out at once
  write("brazilian_timeout.json", brazilian);
  write("ucs_small.json", Scene::resolved_json(data("ucs_small.json")));
  const std::string list = write("failing_list.json", {{"tests", {"ucs_small.json", "brazilian_timeout.json"}}});
  const SceneSet set = SceneSet::load(list);
  RunOptions options;
  const json r = set.run(set.resolve({}), options);
  EXPECT_EQ(r.at("status"), "failed");
  EXPECT_EQ(r.at("reason").get<std::string>().rfind("brazilian: timeout", 0), 0u) << r.at("reason");
  EXPECT_TRUE(r.at("macro").empty());  // a point is all its tests or nothing
  EXPECT_EQ(r.at("test_runs"), 2);
}

TEST(SceneSet, BadListsAreRefusedNamingTheFileAndField) {
  json ucs = Scene::resolved_json(data("ucs_small.json"));
  write("ucs_a.json", ucs);
  json mpa = ucs;
  mpa["parameters"]["Ec_GPa"]["unit"] = "MPa";
  mpa["name"] = "mpa";
  write("ucs_mpa.json", mpa);
  json wide = ucs;
  wide["parameters"]["Ec_GPa"]["high"] = 900;
  wide["name"] = "wide";
  write("ucs_wide.json", wide);
  json brazilian = Scene::resolved_json(data("brazilian_small.json"));
  brazilian["parameters"]["Ec_GPa"]["value"] = 20;
  write("brazilian_other_default.json", brazilian);

  std::string e = error_of(write("l_unit.json", {{"tests", {"ucs_a.json", "ucs_mpa.json"}}}));
  EXPECT_NE(e.find("l_unit.json: tests: parameter \"Ec_GPa\" has unit \"MPa\""), std::string::npos) << e;
  e = error_of(write("l_bounds.json", {{"tests", {"ucs_a.json", "ucs_wide.json"}}}));
  EXPECT_NE(e.find("\"Ec_GPa\" has bounds [0.1, 900]"), std::string::npos) << e;
  e = error_of(write("l_default.json", {{"tests", {"ucs_a.json", "brazilian_other_default.json"}}}));
  EXPECT_NE(e.find("\"Ec_GPa\" has default 20"), std::string::npos) << e;
  e = error_of(write("l_empty.json", {{"tests", json::array()}}));
  EXPECT_NE(e.find("l_empty.json: \"tests\" must be a non-empty list"), std::string::npos) << e;
  e = error_of(write("l_both.json", {{"tests", {"ucs_a.json"}}, {"test", "ucs"}}));
  EXPECT_NE(e.find("l_both.json: a file has either \"test\" (a scene) or \"tests\""), std::string::npos) << e;
  e = error_of(write("l_missing.json", {{"tests", {"nowhere.json"}}}));
  EXPECT_NE(e.find("nowhere.json"), std::string::npos) << e;
  // Two UCS scenes under one name cannot be told apart.
  e = error_of(write("l_same.json", {{"tests", {"ucs_a.json", "ucs_a.json"}}}));
  EXPECT_NE(e.find("run the same test under the same scene name"), std::string::npos) << e;
  // Two UCS scenes with their own names are labelled by them.
  json renamed = ucs;
  renamed["name"] = "other";
  write("ucs_other.json", renamed);
  const SceneSet two = SceneSet::load(write("l_two.json", {{"tests", {"ucs_a.json", "ucs_other.json"}}}));
  EXPECT_EQ(two.label(0), "ucs_small");
  EXPECT_EQ(two.label(1), "other");
}

TEST(SceneSet, ATestThatThrowsFailsThePointWithItsLabel) {
  json brazilian = Scene::resolved_json(data("brazilian_small.json"));
  brazilian["specimen"]["locked_in_stress_pa"] = 1e12;  // more than any packing's overlaps give: run_test throws
  write("brazilian_locked.json", brazilian);
  write("ucs_small.json", Scene::resolved_json(data("ucs_small.json")));
  const SceneSet set = SceneSet::load(write("throwing_list.json", {{"tests", {"ucs_small.json", "brazilian_locked.json"}}}));
  const json r = set.run(set.resolve({}), RunOptions{});
  EXPECT_EQ(r.at("status"), "failed");
  EXPECT_EQ(r.at("reason").get<std::string>().rfind("brazilian: ", 0), 0u) << r.at("reason");
  EXPECT_NE(r.at("reason").get<std::string>().find("locked_in_stress_pa"), std::string::npos) << r.at("reason");
  EXPECT_EQ(r.at("test_runs"), 2);
  EXPECT_GT(r.at("steps").get<double>(), 0.0);  // the UCS that ran is still counted
}

TEST(SceneSet, AFinerListKeepsItsLabelsAndFindsItsScenesFromARelativeFolder) {
  json ucs = Scene::resolved_json(data("ucs_small.json"));
  write("ucs_a.json", ucs);
  ucs["name"] = "other";
  write("ucs_b.json", ucs);  // two UCS scenes: labelled by their names
  const std::string list = write("two_ucs.json", {{"tests", {"ucs_a.json", "ucs_b.json"}}});
  std::filesystem::create_directories(demcal::test::scratch_path("work"));
  const std::string relative =
      std::filesystem::relative(demcal::test::scratch_path("work"), std::filesystem::current_path()).string();
  const std::string finer = SceneSet::write_with_finer_disks(list, 2.0, relative + "/finer.json");
  const SceneSet coarse_set = SceneSet::load(list), finer_set = SceneSet::load(finer);
  ASSERT_EQ(finer_set.size(), 2u);
  EXPECT_EQ(finer_set.label(0), coarse_set.label(0));
  EXPECT_EQ(finer_set.label(1), "other");
  EXPECT_NEAR(specimen_spec(finer_set.scenes()[0], finer_set.resolve({}), 1).radius_min_m,
              specimen_spec(coarse_set.scenes()[0], coarse_set.resolve({}), 1).radius_min_m / 2, 1e-15);
  // A name that cannot label outputs is refused.
  ucs["name"] = "a/b";
  write("ucs_slash.json", ucs);
  const std::string e = error_of(write("slash_list.json", {{"tests", {"ucs_a.json", "ucs_slash.json"}}}));
  EXPECT_NE(e.find("must be letters, digits"), std::string::npos) << e;
}
