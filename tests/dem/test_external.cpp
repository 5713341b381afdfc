// The external test: a scene whose test is another program. Checked with the
// stand-in simulator tests/external/fake_simulator.py (a known response and a
// fault on request) and with demcal-dem itself wrapped as a command, which
// must give the native scene's numbers exactly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/dem/external_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/scene_set.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace demcal::dem;

namespace {

const std::string kSource = DEMCAL_SOURCE_DIR;
const std::string kScene = kSource + "/tests/data/external_fake.json";

struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "demcal_external_XXXXXX").string();
    path = ::mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

json run_point(const json& scene_json, const std::map<std::string, double>& set, std::uint64_t seed,
               const std::string& work, const std::string& origin = kScene) {
  const SceneSet scenes = SceneSet::of({Scene::from_json(scene_json, origin)}, origin, "external");
  RunOptions options;
  options.seed = seed;
  options.work_dir = work;
  return scenes.run(scenes.resolve(set), options);
}

std::string load_error(const json& scene_json) {
  try {
    Scene::from_json(scene_json, kScene);
  } catch (const demcal::Error& e) {
    return e.what();
  }
  return "(loaded)";
}

}  // namespace

TEST(ExternalTest, ReportsTheCommandsOutputsAndKeepsItsFiles) {
  TempDir dir;
  const json r = run_point(Scene::resolved_json(kScene), {{"a_MPa", 2.5}, {"b_MPa", 0.1}}, 7, dir / "run1_seed7");
  ASSERT_EQ(r.at("status"), "ok") << r.dump();
  // y = 2 a + 3 b + 0.01 (seed mod 5), z = a b, as the stand-in computes them in doubles.
  EXPECT_DOUBLE_EQ(r.at("macro").at("y_MPa").get<double>(), 2 * 2.5 + 3 * 0.1 + 0.01 * 2);
  EXPECT_DOUBLE_EQ(r.at("macro").at("z").get<double>(), 2.5 * 0.1);
  EXPECT_EQ(r.at("macro").size(), 2u);                         // the declared outputs ...
  EXPECT_EQ(r.at("extra_outputs").at("w").get<double>(), 1.5);  // ... and the rest beside them
  EXPECT_EQ(r.at("curve").at("stress_MPa"), json({0.0, 2.5, 1.25}));
  const json params = json::parse(text_of(dir / "run1_seed7/params.json"));
  EXPECT_EQ(params.at("seed"), 7);
  EXPECT_EQ(params.at("parameters").at("a_MPa"), 2.5);
  EXPECT_EQ(params.at("parameters").at("mode"), 0.0);
  EXPECT_NE(text_of(dir / "run1_seed7/stdout.txt").find("fake simulator: mode 0, seed 7"), std::string::npos);
  EXPECT_EQ(text_of(dir / "run1_seed7/stderr.txt"), "fake simulator on stderr\n");
  EXPECT_TRUE(fs::exists(dir / "run1_seed7/fake_simulator.py"));  // the input, copied beside them
}

TEST(ExternalTest, EachFaultFailsThePointWithItsReason) {
  const std::vector<std::pair<int, std::string>> faults = {
      {1, "the command reported failure: the specimen collapsed under gravity"},
      {3, "out.json is not JSON (it holds NaN or Infinity"},
      {4, "out.json is not JSON: "},
      {5, "/usr/bin/python3 exited with status 3; stderr: bad things happened"},
      {6, "the command wrote no out.json"}};
  TempDir dir;
  for (const auto& [mode, reason] : faults) {
    const json r = run_point(Scene::resolved_json(kScene), {{"mode", mode}}, 1, dir / ("mode" + std::to_string(mode)));
    EXPECT_EQ(r.at("status"), "failed") << mode;
    EXPECT_NE(r.at("reason").get<std::string>().find(reason), std::string::npos) << r.at("reason");
    EXPECT_TRUE(r.at("macro").empty());
  }
}

TEST(ExternalTest, AHangingCommandIsKilledAtItsTimeout) {
  json scene = Scene::resolved_json(kScene);
  scene["timeout_s"] = 1;
  TempDir dir;
  const json r = run_point(scene, {{"mode", 2}}, 1, dir / "p");
  EXPECT_EQ(r.at("status"), "failed");
  EXPECT_EQ(r.at("reason"), "timeout: /usr/bin/python3 timed out after 1 s (its process group was killed); "
                            "stderr: fake simulator on stderr");
  EXPECT_LT(r.at("wall_s").get<double>(), 5.0);
}

TEST(ExternalTest, AResultIsOnlyWhatThisRunWrote) {
  TempDir dir;
  // A stale out.json from an earlier run of the folder is never read as this run's answer.
  fs::create_directories(dir / "p");
  std::ofstream(dir / "p/out.json") << R"({"status": "ok", "outputs": {"y_MPa": 1, "z": 2}})";
  const json r = run_point(Scene::resolved_json(kScene), {{"mode", 6}}, 1, dir / "p");
  EXPECT_EQ(r.at("status"), "failed");
  // Litter named like demcal's files stays in the command's own folder.
  const json ok = run_point(Scene::resolved_json(kScene), {{"mode", 7}}, 1, dir / "q");
  EXPECT_EQ(ok.at("status"), "ok");
  EXPECT_TRUE(fs::exists(dir / "q/run1_seed1.json"));
  EXPECT_FALSE(fs::exists(dir / "run1_seed1.json"));
}

TEST(ExternalTest, ACommandThatDoesNotExistFailsThePoint) {
  json scene = Scene::resolved_json(kScene);
  scene["command"][0] = "no_such_simulator_4711";
  TempDir dir;
  const json r = run_point(scene, {}, 1, dir / "p");
  EXPECT_EQ(r.at("status"), "failed");
  EXPECT_EQ(r.at("reason"), "command not found: no_such_simulator_4711 (not on PATH)");
}

TEST(ExternalTest, BadScenesNameTheField) {
  auto with = [](const std::function<void(json&)>& change) {
    json scene = Scene::resolved_json(kScene);
    change(scene);
    return load_error(scene);
  };
  EXPECT_EQ(with([](json& s) { s["command"].push_back("--c={c_MPa}"); }),
            kScene + ": command[5]: placeholder {c_MPa} is neither a parameter of the scene nor one of {seed}, "
                     "{params_json}, {out_json}, {workdir}, {scene_dir} (parameters: {a_MPa}, {b_MPa}, {mode})");
  EXPECT_EQ(with([](json& s) { s.erase("command"); }),
            kScene + ": command: missing (a list of arguments, program first: [\"python3\", \"run_point.py\", ...])");
  EXPECT_EQ(with([](json& s) { s["command"] = {"python3", 4}; }),
            kScene + ": command[1]: must be a string (the command runs without a shell)");
  EXPECT_EQ(with([](json& s) { s["timeout_s"] = -1; }), kScene + ": timeout_s: must be a positive number of seconds");
  EXPECT_EQ(with([](json& s) { s["workdir"] = ""; }), kScene + ": workdir: must be \"per_point\" or a folder");
  EXPECT_EQ(with([](json& s) { s["inputs"] = {"no_such_driver.py"}; }),
            kScene + ": inputs[0]: " + kSource + "/tests/data/no_such_driver.py is not a file");
  EXPECT_EQ(with([](json& s) { s.erase("outputs"); }),
            kScene + ": outputs: missing (an object of name: {\"unit\": ...} for what the command reports)");
  EXPECT_NE(with([](json& s) { s["outputs"]["y_MPa"]["unit"] = "furlong"; }).find(kScene + ": outputs.y_MPa.unit"),
            std::string::npos);
  EXPECT_NE(with([](json& s) { s["specimen"] = json::object(); }).find("unknown field \"specimen\""), std::string::npos)
      << with([](json& s) { s["specimen"] = json::object(); });
}

TEST(ExternalTest, EditingADriverChangesTheFingerprintAndADescriptionDoesNot) {
  TempDir dir;
  fs::copy_file(kSource + "/tests/external/fake_simulator.py", dir / "driver.py");
  json scene = Scene::resolved_json(kScene);
  scene["inputs"] = {"driver.py"};
  const std::string origin = dir / "scene.json";
  const std::string before = Scene::from_json(scene, origin).fingerprint();
  scene["description"] = "another text";
  EXPECT_EQ(Scene::from_json(scene, origin).fingerprint(), before);
  std::ofstream(dir / "driver.py", std::ios::app) << "# edited\n";
  EXPECT_NE(Scene::from_json(scene, origin).fingerprint(), before);
}

TEST(ExternalTest, PlaceholdersExpandAtFullPrecision) {
  json scene = Scene::resolved_json(kScene);
  scene["command"] = {"prog", "{a_MPa}", "--seed={seed}", "{workdir}/x", "{scene_dir}", "{not a placeholder}", "{}"};
  const Scene s = Scene::from_json(scene, kScene);
  const std::vector<std::string> argv =
      expand_command(s.external(), {{"a_MPa", 0.1}, {"b_MPa", 1.0 / 3}, {"mode", 0}}, 12, "P", "O", "/w");
  EXPECT_EQ(argv, (std::vector<std::string>{"prog", "0.1", "--seed=12", "/w/x", kSource + "/tests/data",
                                            "{not a placeholder}", "{}"}));
}

TEST(ExternalTest, DemcalDemWrappedAsACommandGivesTheNativeNumbers) {
  const std::string native_scene = kSource + "/tests/data/ucs_small.json";
  json scene = {{"name", "wrapped"}, {"test", "external"},
                {"command", {"/usr/bin/python3", kSource + "/tests/external/demcal_dem_driver.py",
                             std::string(DEMCAL_BIN_DIR) + "/demcal-dem", native_scene, "{params_json}", "{out_json}"}},
                {"parameters", Scene::resolved_json(native_scene).at("parameters")},
                {"outputs", json::object()}};
  const SceneSet native = SceneSet::load(native_scene);
  for (const OutputSpec& o : native.outputs())
    if (o.always) scene["outputs"][o.name] = {{"unit", o.unit}};
  TempDir dir;
  const std::map<std::string, double> set = {{"pb_sigma_c_MPa", 12.5}, {"kn_ks", 1.7}};
  const json wrapped = run_point(scene, set, 3, dir / "p", dir / "wrapped.json");
  RunOptions options;
  options.seed = 3;
  const json direct = native.run(native.resolve(set), options);
  ASSERT_EQ(direct.at("status"), "ok");
  ASSERT_EQ(wrapped.at("status"), "ok") << wrapped.at("reason");
  for (const auto& [name, value] : scene.at("outputs").items())
    EXPECT_EQ(wrapped.at("macro").at(name).get<double>(), direct.at("macro").at(name).get<double>()) << name;
}
