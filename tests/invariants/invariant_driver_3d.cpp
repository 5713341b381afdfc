// The invariant driver's 3D part: every registered 3D contact model passes
// the same checks, from one data file each (tests/invariants/models3d/NAME.json:
// {"model", "parameters", "stress_keys", "steps", "stability": {"parameters",
// "radius_m", "density_kg_m3"}}, and for a bonded model "bonds":
// {"gap_tolerance_m", "seed"}), on a cloud of 576 spheres colliding in a box
// of six planes (no gravity, so the law's scaling is exact); a bonded model's
// cloud is bonded across gaps up to the tolerance first, and some bonds break:
//   - 1, 2 and 3 threads, and the spheres entering in a shuffled order, give
//     the same bits for every sphere and the same break log;
//   - every stress_keys parameter x 4 and the velocities x 2 give the same run
//     in half the time: positions the same bits, velocities x 2 exactly;
//   - a pressed pair between two walls and a sphere resting on a floor stay
//     stable for 4e4 steps at the default safety factor, dashpots included;
//   - a golden per model (golden/model3d_NAME.json; DEMCAL_UPDATE_GOLDEN=1
//     rewrites it, in a commit that says why).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include <nlohmann/json.hpp>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

namespace {

using namespace demcal::dem3d;
using json = nlohmann::json;
namespace fs = std::filesystem;

const std::string kHere = std::string(DEMCAL_SOURCE_DIR) + "/tests/invariants/";

std::vector<std::string> model_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kHere + "models3d"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  return json::parse(in);
}

struct Cloud {
  std::vector<Vec3> centre, velocity;
  std::vector<double> radius;
};

// 576 spheres of radius 0.8-1.1 mm on a jittered 2.25 mm lattice, each with a random velocity up to 0.3 m/s.
Cloud cloud() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud c;
  for (std::size_t k = 0; k < 576; ++k) {
    const double x = 0.0012 + 0.00225 * static_cast<double>(k % 8), y = 0.0012 + 0.00225 * static_cast<double>(k / 8 % 8),
                 z = 0.0012 + 0.00225 * static_cast<double>(k / 64);
    c.centre.push_back({x + 1e-4 * u(rng), y + 1e-4 * u(rng), z + 1e-4 * u(rng)});
    c.radius.push_back(0.00095 + 0.00015 * u(rng));
    c.velocity.push_back({0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)});
  }
  return c;
}

class Model3DInvariants : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    data_ = read_json(kHere + "models3d/" + GetParam() + ".json");
    ASSERT_EQ(data_.at("model"), GetParam()) << "a model's data file is named after it";
  }

  // The cloud in its box, the spheres entering in the order `order_seed` gives (0: by id).
  World world(int threads, std::uint64_t order_seed = 0, double stress_scale = 1.0) const {
    WorldSettings settings;
    settings.threads = threads;
    settings.min_spheres_per_thread = 1;
    World w(settings);
    json p = data_.at("parameters");
    for (const auto& key : data_.at("stress_keys")) p[key.get<std::string>()] = stress_scale * p.at(key.get<std::string>()).get<double>();
    const auto model = w.add_model(ContactModelRegistry::instance().create(GetParam(), p, "invariants"));
    w.assign(0, 0, model);
    w.assign(0, 1, model);
    w.walls = {make_plane({0, 0, 0}, {0, 0, 1}), make_plane({0, 0, 0.0205}, {0, 0, -1}), make_plane({0, 0, 0}, {1, 0, 0}),
               make_plane({0.0185, 0, 0}, {-1, 0, 0}), make_plane({0, 0, 0}, {0, 1, 0}),
               make_plane({0, 0.0185, 0}, {0, -1, 0})};
    const Cloud c = cloud();
    std::vector<std::size_t> order(c.centre.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    if (order_seed) std::shuffle(order.begin(), order.end(), std::mt19937_64(order_seed));
    const double speed = std::sqrt(stress_scale);
    for (std::size_t k : order) {
      const std::size_t i = w.spheres.add_sphere(c.centre[k], c.radius[k], 2650, 0, static_cast<std::int64_t>(k));
      w.spheres.set_velocity(i, speed * c.velocity[k]);
    }
    install_bonds(w);
    return w;
  }
  // A bonded model's bonds (none for a model without a "bonds" entry).
  void install_bonds(World& w) const {
    if (!data_.contains("bonds")) return;
    const json& b = data_.at("bonds");
    const std::size_t installed = w.install_bonds(b.at("gap_tolerance_m").get<double>(), b.at("seed").get<std::uint64_t>());
    if (installed == 0) throw std::runtime_error(GetParam() + ": no bond installed (gap_tolerance_m too small?)");
  }
  std::uint64_t steps() const { return data_.at("steps").get<std::uint64_t>(); }

  json data_;
};

std::map<std::uint32_t, std::vector<double>> state_by_id(const World& w) {
  std::map<std::uint32_t, std::vector<double>> out;
  const Spheres& s = w.spheres;
  for (std::size_t i = 0; i < s.size(); ++i)
    out[s.id[i]] = {s.x[i], s.y[i], s.z[i], s.vx[i], s.vy[i], s.vz[i], s.wx[i], s.wy[i], s.wz[i]};
  return out;
}

::testing::AssertionResult same_bits(const std::map<std::uint32_t, std::vector<double>>& a,
                                     const std::map<std::uint32_t, std::vector<double>>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << "sphere counts differ";
  for (const auto& [id, values] : a)
    if (std::memcmp(values.data(), b.at(id).data(), values.size() * sizeof(double)) != 0)
      return ::testing::AssertionFailure() << "sphere " << id << " differs";
  return ::testing::AssertionSuccess();
}

TEST_P(Model3DInvariants, ThreadsAndShuffledSpheresGiveTheSameBits) {
  World one = world(1);
  one.run(steps());
  ASSERT_GT(one.touching_pairs(), 0u);
  const auto expected = state_by_id(one);
  for (int threads : {2, 3}) {
    World w = world(threads);
    w.run(steps());
    EXPECT_EQ(w.threads_in_use(), threads);
    EXPECT_TRUE(same_bits(state_by_id(w), expected)) << threads << " threads";
  }
  World shuffled = world(2, 17);
  shuffled.run(steps());
  EXPECT_TRUE(same_bits(state_by_id(shuffled), expected)) << "shuffled";
  if (data_.contains("bonds")) {
    EXPECT_GT(one.breaks().size(), 0u) << "no bond broke: the check does not reach the break test";
    EXPECT_GT(one.bonded_pairs(), 0u) << "every bond broke: the check does not reach an intact bond";
    ASSERT_EQ(shuffled.breaks().size(), one.breaks().size());
    for (std::size_t k = 0; k < one.breaks().size(); ++k) {
      const auto &a = one.breaks()[k], &b = shuffled.breaks()[k];
      EXPECT_TRUE(a.time_s == b.time_s && a.x_m == b.x_m && a.y_m == b.y_m && a.z_m == b.z_m && a.mode == b.mode)
          << "break " << k;
    }
  }
  // The golden: the run's summary, bit for bit.
  double x_sum = 0;
  for (const auto& [id, v] : expected) x_sum += v[0] + v[1] + v[2];
  json now = {{"kinetic_energy_j", one.kinetic_energy()}, {"position_sum_m", x_sum}, {"dt_s", one.dt_s()},
              {"rebuilds", one.rebuilds()}, {"touching_pairs", one.touching_pairs()}};
  if (data_.contains("bonds")) now["breaks"] = one.breaks().size(), now["bonded_pairs"] = one.bonded_pairs();
  const std::string path = kHere + "golden/model3d_" + GetParam() + ".json";
  const char* update = std::getenv("DEMCAL_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    std::ofstream(path) << now.dump(1) << "\n";
    return;
  }
  ASSERT_TRUE(fs::exists(path)) << path << ": no golden yet (DEMCAL_UPDATE_GOLDEN=1 writes it)";
  EXPECT_EQ(read_json(path), now) << path << " (a golden moves only with a change of physics)";
}

TEST_P(Model3DInvariants, StressesTimesFourRunTheSameInHalfTheTime) {
  World base = world(1), scaled = world(1, 0, 4.0);
  base.run(steps());
  scaled.run(steps());
  EXPECT_EQ(scaled.dt_s(), 0.5 * base.dt_s());
  EXPECT_EQ(scaled.breaks().size(), base.breaks().size());
  const Spheres &a = base.spheres, &b = scaled.spheres;
  ASSERT_EQ(a.id, b.id);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(b.x[i], a.x[i]) << "sphere " << a.id[i];
    ASSERT_EQ(b.z[i], a.z[i]) << "sphere " << a.id[i];
    ASSERT_EQ(b.vy[i], 2 * a.vy[i]) << "sphere " << a.id[i];
    ASSERT_EQ(b.wx[i], 2 * a.wx[i]) << "sphere " << a.id[i];
  }
}

TEST_P(Model3DInvariants, APressedPairAndARestingSphereStayStable) {
  const json& s = data_.at("stability");
  const double r = s.at("radius_m"), rho = s.at("density_kg_m3");
  const auto make = [&](double gravity) {
    WorldSettings settings;
    settings.damping = 0.0;
    settings.gravity_m_s2 = {0, 0, gravity};
    World w(settings);
    const auto model = w.add_model(ContactModelRegistry::instance().create(GetParam(), s.at("parameters"), "stability"));
    w.assign(0, 0, model);
    w.assign(0, 1, model);
    return w;
  };
  const double overlap = 0.01 * r;
  {
    World w = make(0.0);
    w.spheres.add_sphere({r - overlap, 0, 0}, r, rho, 0);
    w.spheres.add_sphere({3 * r - 2 * overlap, 0, 0}, r, rho, 0);
    w.walls = {make_plane({0, 0, 0}, {1, 0, 0}), make_plane({4 * r - 3 * overlap, 0, 0}, {-1, 0, 0})};
    w.spheres.set_spin(0, {0, 0, 1e-3});
    w.spheres.set_spin(1, {0, 0, -1e-3});
    w.refresh();
    if (data_.contains("bonds")) {
      ASSERT_EQ(w.install_bonds(0.1 * r, 1), 1u) << "the pressed pair is bonded";
    }
    double largest_spin = 0, first_energy = 0, last_energy = 0;
    for (int k = 0; k < 400; ++k) {
      for (int step = 0; step < 100; ++step) {
        w.step();
        double& window = k < 100 ? first_energy : last_energy;
        window = std::max(window, w.kinetic_energy());
      }
      largest_spin = std::max({largest_spin, norm(w.spheres.spin(0)), norm(w.spheres.spin(1))});
      if (k == 299) last_energy = 0;  // the last 1e4 steps against the first
    }
    EXPECT_LT(largest_spin, 1e-2) << "the pressed pair's spin grew from 1e-3 rad/s (dt " << w.dt_s() << " s)";
    EXPECT_LE(last_energy, 2.0 * first_energy + 1e-30) << "the pressed pair gained energy (dt " << w.dt_s() << " s)";
  }
  {
    World w = make(-9.81);
    w.spheres.add_sphere({0, 0, r}, r, rho, 0);
    w.walls = {make_plane({0, 0, 0}, {0, 0, 1})};
    w.refresh();
    double highest = 0, fastest = 0;
    for (int k = 0; k < 40; ++k) {
      w.run(1000);
      if (k >= 20) highest = std::max(highest, w.spheres.z[0]), fastest = std::max(fastest, std::fabs(w.spheres.vz[0]));
    }
    EXPECT_TRUE(std::isfinite(w.spheres.z[0]));
    EXPECT_LT(highest, 1.01 * r) << "the resting sphere bounced off its floor (dt " << w.dt_s() << " s)";
    EXPECT_LT(fastest, 0.01 * std::sqrt(9.81 * r)) << "the resting sphere did not settle (dt " << w.dt_s() << " s)";
  }
}

std::string name_of(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

INSTANTIATE_TEST_SUITE_P(Models3D, Model3DInvariants, ::testing::ValuesIn(model_files()), name_of);

TEST(Invariants, EveryRegistered3DModelHasItsDataFile) {
  const std::vector<std::string> models = model_files();
  for (const std::string& name : ContactModelRegistry::instance().names())
    EXPECT_TRUE(std::count(models.begin(), models.end(), name)) << "tests/invariants/models3d/" << name << ".json";
}

}  // namespace
