// The invariant driver: every registered contact model and lab test passes the
// same checks, by data (in the manner of LAMMPS's one driver over a YAML file
// per style). A model or test joins with one data file, read at start:
//
//   tests/invariants/models/NAME.json      {"model", "scene", "side_walls", "steps" | "load_until_breaks",
//                                           "exact_scaling", "stability": {"parameters", "radius_m",
//                                           "density_kg_m3", "thickness_m"?}}
//   tests/invariants/lab_tests/NAME.json   {"test", "scene", "seed", "particles"? (false: none of ours),
//                                           "why_no_particles"?, "scale_by_velocity"?: [JSON pointers],
//                                           "scale_by_stress"?: [JSON pointers]}
//
// "scene" is relative to the data file. Checks, through the models' and
// tests' public interfaces only:
//   - 1, 2 and 3 threads give the same bits (a model's world: every disk,
//     wall force, break, rebuild and the time step; a test: every output);
//   - particles entering in a shuffled order (ids kept) give the same bits;
//   - exact scaling where declared (or, for a test whose stress inputs are not
//     parameters, with the data file's scale_by_stress scaled too): every
//     stress-like parameter x 4 and the loading velocity x 2 give the same run
//     in time halved (positions the same bits, velocities x 2, forces and
//     stress outputs x 4);
//   - a model's pressed pair and resting particle stay stable for 4e4 steps
//     at the default safety factor, its dashpots included;
//   - a golden per model and per test (tests/invariants/golden/KIND_NAME.json;
//     DEMCAL_UPDATE_GOLDEN=1 rewrites it, in a commit that says why).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "../common/load_until_breaks.hpp"
#include "../common/same_bits.hpp"
#include "../common/scratch.hpp"
#include "demcal/core/units.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/scene.hpp"

namespace {

using namespace demcal;
using namespace demcal::dem;
using json = nlohmann::json;
namespace fs = std::filesystem;

const std::string kHere = std::string(DEMCAL_SOURCE_DIR) + "/tests/invariants/";

std::vector<std::string> data_files(const std::string& kind) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kHere + kind))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  return json::parse(in);
}

json data_of(const std::string& kind, const std::string& name) { return read_json(kHere + kind + "/" + name + ".json"); }
std::string scene_path(const std::string& kind, const json& data) {
  return kHere + kind + "/" + data.at("scene").get<std::string>();
}

// The golden of KIND NAME: compared with `now`, or written when DEMCAL_UPDATE_GOLDEN is set.
void expect_golden(const std::string& kind, const std::string& name, const json& now) {
  const std::string path = kHere + "golden/" + kind + "_" + name + ".json";
  const char* update = std::getenv("DEMCAL_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    std::ofstream(path) << now.dump(1) << "\n";
    return;
  }
  ASSERT_TRUE(fs::exists(path)) << path << ": no golden yet (DEMCAL_UPDATE_GOLDEN=1 writes it)";
  const json golden = read_json(path);
  for (const auto& [key, value] : golden.items()) {
    ASSERT_TRUE(now.contains(key)) << path << ": " << key;
    EXPECT_EQ(now.at(key), value) << path << ": " << key << " (a golden moves only with a change of physics)";
  }
  EXPECT_EQ(now.size(), golden.size()) << path;
}

// The scene with every stress-like parameter's value times k (bounds opened),
// and the values at `velocity_pointers` times sqrt(k), at `stress_pointers` times k.
Scene scaled_scene(const std::string& path, double k, const std::vector<std::string>& velocity_pointers,
                   const std::vector<std::string>& stress_pointers) {
  json j = Scene::resolved_json(path);
  for (auto& [name, p] : j.at("parameters").items())
    if (is_stress_like(quantity_of_unit(p.at("unit").get<std::string>(), name))) {
      p["value"] = k * p.at("value").get<double>();
      p["high"] = 1e300;
    }
  const auto times = [&](const std::string& pointer, double factor) {
    json& v = j.at(json::json_pointer(pointer));
    if (v.is_array())
      for (json& x : v) x = factor * x.get<double>();
    else
      v = factor * v.get<double>();
  };
  for (const std::string& p : velocity_pointers) times(p, std::sqrt(k));
  for (const std::string& p : stress_pointers) times(p, k);
  return Scene::from_json(j, path);
}

// ---------------------------------------------------------------- contact models

class ModelInvariants : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    data_ = data_of("models", GetParam());
    ASSERT_EQ(data_.at("model"), GetParam()) << "a model's data file is named after it";
    path_ = scene_path("models", data_);
  }

  // The data file's scene as a platen world, its particles in the order `order_seed` gives.
  World world(const Scene& scene, int threads, std::uint64_t order_seed = 0) const {
    const auto parameters = scene.resolve({});
    RunOptions options;
    options.threads = threads;
    options.min_disks_per_thread = 1;  // these specimens are small
    options.particle_order_seed = order_seed;
    const Specimen s = cached_specimen(specimen_spec(scene, parameters, kSeed), test::scratch_path("cache"));
    World w = make_platen_world(scene, parameters, s, kSeed, nullptr, nullptr, data_.value("side_walls", false),
                                nullptr, &options);
    w.refresh();
    return w;
  }

  // Runs the data file's loading: a set number of steps, or until bonds break and as many steps more.
  void load(World& w) const {
    if (data_.contains("load_until_breaks")) {
      const std::size_t breaks = data_.at("load_until_breaks").get<std::size_t>();
      const std::uint64_t steps = test::load_until_breaks(w, breaks);
      ASSERT_GE(w.breaks().size(), breaks) << "the run should reach bond breakage";
      w.run(steps);
    } else {
      w.run(data_.at("steps").get<std::uint64_t>());
    }
  }

  static constexpr std::uint64_t kSeed = 2;
  json data_;
  std::string path_;
};

TEST_P(ModelInvariants, OneTwoAndThreeThreadsGiveTheSameBits) {
  const Scene scene = Scene::load(path_);
  World serial = world(scene, 1);
  ASSERT_EQ(serial.threads_in_use(), 1);
  load(serial);
  for (int threads : {2, 3}) {
    World threaded = world(scene, threads);
    ASSERT_EQ(threaded.threads_in_use(), threads);
    threaded.run(serial.steps_done());
    SCOPED_TRACE(std::to_string(threads) + " threads");
    test::expect_same_bits(serial, threaded);
  }
  // The golden: what the serial run left.
  json summary;
  double x = 0, y = 0, vx = 0, vy = 0, w = 0;
  for (std::size_t k = 0; k < serial.bodies.size(); ++k) {
    x += serial.bodies.x[k];
    y += serial.bodies.y[k];
    vx += serial.bodies.vx[k];
    vy += serial.bodies.vy[k];
    w += serial.bodies.w[k];
  }
  summary["steps"] = serial.steps_done();
  summary["dt_s"] = serial.dt_s();
  summary["sum_x_m"] = x;
  summary["sum_y_m"] = y;
  summary["sum_vx_m_s"] = vx;
  summary["sum_vy_m_s"] = vy;
  summary["sum_w_rad_s"] = w;
  summary["breaks"] = serial.breaks().size();
  summary["top_platen_fy_n"] = serial.walls[1].fy;
  expect_golden("model", GetParam(), summary);
}

TEST_P(ModelInvariants, ShuffledParticlesGiveTheSameBitsPerParticle) {
  const Scene scene = Scene::load(path_);
  World a = world(scene, 1), b = world(scene, 1, 7);
  ASSERT_NE(a.bodies.id, b.bodies.id) << "the shuffle should change the order";
  load(a);
  b.run(a.steps_done());
  test::expect_same_bits_per_id(a, b);
}

TEST_P(ModelInvariants, ExactScalingWhereDeclared) {
  if (!data_.at("exact_scaling").get<bool>()) GTEST_SKIP() << data_.value("why_not_exact_scaling", "not declared");
  const Scene scene = Scene::load(path_);
  const Scene scaled = scaled_scene(path_, 4.0, {"/loading/platen_velocity_m_s"}, {});
  World a = world(scene, 1), b = world(scaled, 1);
  load(a);
  b.run(a.steps_done());
  EXPECT_EQ(b.dt_s(), 0.5 * a.dt_s());
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    ASSERT_EQ(a.bodies.x[k], b.bodies.x[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.y[k], b.bodies.y[k]) << "disk " << k;
    ASSERT_EQ(2 * a.bodies.vx[k], b.bodies.vx[k]) << "disk " << k;
    ASSERT_EQ(2 * a.bodies.w[k], b.bodies.w[k]) << "disk " << k;
  }
  EXPECT_EQ(4 * a.walls[1].fy, b.walls[1].fy);
  EXPECT_EQ(a.breaks().size(), b.breaks().size());
}

// A model's two smallest dynamic systems at the default safety factor and no
// local damping (as dynamic scenes run): two equal disks pressed together
// between two walls with a small relative spin, and one disk resting on a
// floor under gravity. Neither may gain energy: an explicit step too long for
// the dashpots (whose effective masses can be far below the disks') shows as
// a spin or bounce growing by orders of magnitude.
TEST_P(ModelInvariants, APressedPairAndARestingParticleStayStable) {
  const json& s = data_.at("stability");
  const double r = s.at("radius_m"), rho = s.at("density_kg_m3"), t = s.value("thickness_m", 1.0);
  const auto make = [&](double gravity) {
    WorldSettings settings;
    settings.damping = 0.0;
    settings.thickness_m = t;
    settings.gravity_y_m_s2 = gravity;
    World w(settings);
    const auto model = w.add_model(ContactModelRegistry::instance().create(GetParam(), s.at("parameters"), "stability"));
    w.assign(0, 0, model);
    w.assign(0, 1, model);
    return w;
  };
  const auto wall = [](double x0, double y0, double x1, double y1, double nx, double ny) {
    Wall w;
    w.x0 = x0, w.y0 = y0, w.x1 = x1, w.y1 = y1, w.inward_nx = nx, w.inward_ny = ny, w.group = 1;
    return w;
  };
  const double overlap = 0.01 * r;
  {
    World w = make(0.0);
    w.bodies.add_disk(r - overlap, 0, r, rho, t, 0);
    w.bodies.add_disk(3 * r - 2 * overlap, 0, r, rho, t, 0);
    w.walls = {wall(0, -2 * r, 0, 2 * r, 1, 0), wall(4 * r - 3 * overlap, -2 * r, 4 * r - 3 * overlap, 2 * r, -1, 0)};
    w.bodies.w[0] = 1e-3;
    w.bodies.w[1] = -1e-3;
    w.refresh();
    // Without damping the pair rings between its walls at the energy it started with; it may lose it, never gain.
    // (two modes beat, so a window's largest kinetic energy varies; an unstable step grows it by orders of magnitude).
    double largest_spin = 0, first_energy = 0, last_energy = 0;
    for (int k = 0; k < 400; ++k) {
      for (int s = 0; s < 100; ++s) {
        w.step();
        (k < 100 ? first_energy : last_energy) = std::max(k < 100 ? first_energy : last_energy, w.kinetic_energy());
      }
      largest_spin = std::max({largest_spin, std::fabs(w.bodies.w[0]), std::fabs(w.bodies.w[1])});
      if (k == 299) last_energy = 0;  // the last 1e4 steps against the first
    }
    EXPECT_LT(largest_spin, 1e-2) << "the pressed pair's spin grew from 1e-3 rad/s (dt " << w.dt_s() << " s)";
    EXPECT_LE(last_energy, 2.0 * first_energy + 1e-30)
        << "the pressed pair gained energy (dt " << w.dt_s() << " s): " << first_energy << " J at first, " << last_energy
        << " J at the end";
  }
  {
    World w = make(-9.81);
    w.bodies.add_disk(0, r, r, rho, t, 0);
    w.walls = {wall(-4 * r, 0, 4 * r, 0, 0, 1)};
    w.refresh();
    double highest = 0, fastest = 0;
    for (int k = 0; k < 40; ++k) {
      w.run(1000);
      if (k >= 20) {
        highest = std::max(highest, w.bodies.y[0]);
        fastest = std::max(fastest, std::fabs(w.bodies.vy[0]));
      }
    }
    EXPECT_TRUE(std::isfinite(w.bodies.y[0]));
    EXPECT_LT(highest, 1.01 * r) << "the resting particle bounced off its floor (dt " << w.dt_s() << " s)";
    EXPECT_LT(fastest, 0.01 * std::sqrt(9.81 * r)) << "the resting particle did not settle (dt " << w.dt_s() << " s)";
  }
}

std::string name_of(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

INSTANTIATE_TEST_SUITE_P(Models, ModelInvariants, ::testing::ValuesIn(data_files("models")), name_of);

// ---------------------------------------------------------------- lab tests

class LabTestInvariants : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    data_ = data_of("lab_tests", GetParam());
    ASSERT_EQ(data_.at("test"), GetParam()) << "a lab test's data file is named after it";
    path_ = scene_path("lab_tests", data_);
  }

  TestResult run(const Scene& scene, int threads, std::uint64_t order_seed = 0) const {
    RunOptions options;
    options.seed = data_.at("seed").get<std::uint64_t>();
    options.cache_dir = test::scratch_path("cache");
    options.work_dir = test::scratch_path("work_" + GetParam() + "_" + std::to_string(threads) + "_" +
                                          std::to_string(order_seed) + "_" + std::to_string(++runs_));
    options.threads = threads;
    options.min_disks_per_thread = 1;
    options.particle_order_seed = order_seed;
    TestResult r = run_test(scene, scene.resolve({}), options);
    EXPECT_TRUE(r.ok) << GetParam() << ": " << r.reason;
    return r;
  }

  bool has_particles() const { return data_.value("particles", true); }

  json data_;
  std::string path_;
  mutable int runs_ = 0;
};

void expect_same_outputs(const TestResult& a, const TestResult& b) {
  ASSERT_EQ(a.macro.size(), b.macro.size());
  for (const auto& [name, value] : a.macro) {
    ASSERT_TRUE(b.macro.count(name)) << name;
    EXPECT_EQ(value, b.macro.at(name)) << name << " (difference " << value - b.macro.at(name) << ")";
  }
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.dt_s, b.dt_s);
  EXPECT_EQ(a.ended_by, b.ended_by);
}

TEST_P(LabTestInvariants, OneTwoAndThreeThreadsGiveTheSameOutputs) {
  const Scene scene = Scene::load(path_);
  const TestResult serial = run(scene, 1);
  ASSERT_FALSE(serial.macro.empty());
  if (has_particles()) {
    EXPECT_EQ(serial.threads, 1);
    for (int threads : {2, 3}) {
      const TestResult threaded = run(scene, threads);
      SCOPED_TRACE(std::to_string(threads) + " threads");
      EXPECT_EQ(threaded.threads, threads);
      expect_same_outputs(serial, threaded);
    }
  } else {
    expect_same_outputs(serial, run(scene, 1));  // rerun: the same numbers
  }
  json golden(serial.macro);
  golden["steps"] = serial.steps;
  expect_golden("lab_test", GetParam(), golden);
}

TEST_P(LabTestInvariants, ShuffledParticlesGiveTheSameOutputs) {
  if (!has_particles()) GTEST_SKIP() << data_.at("why_no_particles").get<std::string>();
  const Scene scene = Scene::load(path_);
  expect_same_outputs(run(scene, 1), run(scene, 1, 7));
}

TEST_P(LabTestInvariants, ExactScalingWhereDeclared) {
  const Scene scene = Scene::load(path_);
  // Declared by the test, or shown for the law when the data file names the stress inputs that must scale too
  // (a biaxial series' confinements).
  const bool declared = scene.lab_test().exact_scaling() && (!scene.is_external() || scene.external().exact_scaling);
  if (!declared && !data_.contains("scale_by_stress")) GTEST_SKIP() << "the test declares no exact scaling";
  const Scene scaled = scaled_scene(path_, 4.0, data_.value("scale_by_velocity", std::vector<std::string>{}),
                                    data_.value("scale_by_stress", std::vector<std::string>{}));
  const TestResult a = run(scene, 1), b = run(scaled, 1);
  ASSERT_EQ(a.macro.size(), b.macro.size());
  for (const OutputSpec& o : scene.lab_test().outputs(scene)) {
    if (!a.macro.count(o.name)) continue;
    const double factor = is_stress_like(quantity_of_unit(o.unit, o.name)) ? 4.0 : 1.0;
    EXPECT_EQ(b.macro.at(o.name), factor * a.macro.at(o.name)) << o.name;
  }
  EXPECT_EQ(a.steps, b.steps);
}

INSTANTIATE_TEST_SUITE_P(LabTests, LabTestInvariants, ::testing::ValuesIn(data_files("lab_tests")), name_of);

// ---------------------------------------------------------------- coverage

TEST(Invariants, EveryRegisteredModelAndTestHasItsDataFile) {
  const std::vector<std::string> models = data_files("models"), tests = data_files("lab_tests");
  for (const std::string& name : ContactModelRegistry::instance().names())
    EXPECT_TRUE(std::count(models.begin(), models.end(), name)) << "tests/invariants/models/" << name << ".json";
  for (const std::string& name : LabTestRegistry::instance().names())
    EXPECT_TRUE(std::count(tests.begin(), tests.end(), name)) << "tests/invariants/lab_tests/" << name << ".json";
}

}  // namespace
