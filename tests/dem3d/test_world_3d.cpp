// The 3D world's reproducibility: the same bits on 1, 2 and 3 threads and
// with the spheres added in another order; a neighbour list that keeps every
// pair within the skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <set>
#include <random>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

struct Placed {
  Vec3 centre;
  double radius;
};

// Spheres of radius 0.8-1.1 mm on a jittered 2.25 mm lattice in a 20 mm box,
// each with a random velocity up to 0.3 m/s, so they collide at once.
struct Cloud {
  std::vector<Placed> placed;
  std::vector<Vec3> velocity;
};
Cloud cloud(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud out;
  for (std::size_t k = 0; k < count; ++k) {
    const double x = 0.0012 + 0.00225 * static_cast<double>(k % 8), y = 0.0012 + 0.00225 * static_cast<double>(k / 8 % 8),
                 z = 0.0012 + 0.00225 * static_cast<double>(k / 64);
    out.placed.push_back({{x + 1e-4 * u(rng), y + 1e-4 * u(rng), z + 1e-4 * u(rng)}, 0.00095 + 0.00015 * u(rng)});
    out.velocity.push_back({0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)});
  }
  return out;
}

World box_world(const Cloud& cloud, const std::vector<std::size_t>& order, int threads, bool clumped = false) {
  WorldSettings settings;
  settings.gravity_m_s2 = {0, 0, -1000};  // a hundred g: a packing forms within the test's steps
  settings.threads = threads;
  settings.min_spheres_per_thread = 50;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e8}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e8}, {"kn_ks", 1.5}, {"friction", 0.3}}, "test")));
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  world.walls.push_back(make_plane({0, 0, 0}, {1, 0, 0}));
  world.walls.push_back(make_plane({0.02, 0, 0}, {-1, 0, 0}));
  world.walls.push_back(make_plane({0, 0, 0}, {0, 1, 0}));
  world.walls.push_back(make_plane({0, 0.02, 0}, {0, -1, 0}));
  for (std::size_t k : order) {
    const std::size_t i =
        world.spheres.add_sphere(cloud.placed[k].centre, cloud.placed[k].radius, 2650, 0, static_cast<std::int64_t>(k));
    world.spheres.set_velocity(i, cloud.velocity[k]);
  }
  // Dumbbells: spheres of ids 2k and 2k + 1 (neighbours on the lattice) as one clump, added in id order.
  for (std::size_t k = 0; clumped && k + 1 < cloud.placed.size(); k += 2) {
    const std::size_t a = world.index_of(static_cast<std::uint32_t>(k)), b = world.index_of(static_cast<std::uint32_t>(k + 1));
    const ClumpShape shape = clump_of_spheres({world.spheres.position(a), world.spheres.position(b)},
                                              {world.spheres.radius[a], world.spheres.radius[b]}, 2650);
    world.add_clump({a, b}, shape.mass_kg, shape.principal_inertia_kg_m2, shape.orientation, shape.centre_m);
  }
  return world;
}

// Every sphere's state by id, as bits.
std::map<std::uint32_t, std::vector<double>> state_by_id(const World& w) {
  std::map<std::uint32_t, std::vector<double>> out;
  const Spheres& s = w.spheres;
  for (std::size_t i = 0; i < s.size(); ++i)
    out[s.id[i]] = {s.x[i], s.y[i], s.z[i], s.vx[i], s.vy[i], s.vz[i], s.wx[i], s.wy[i], s.wz[i]};
  return out;
}

bool same_bits(const std::map<std::uint32_t, std::vector<double>>& a, const std::map<std::uint32_t, std::vector<double>>& b) {
  if (a.size() != b.size()) return false;
  for (const auto& [id, values] : a) {
    const auto it = b.find(id);
    if (it == b.end() || std::memcmp(values.data(), it->second.data(), values.size() * sizeof(double)) != 0) return false;
  }
  return true;
}

}  // namespace

TEST(World3D, ThreadsAndSphereOrderGiveTheSameBits) {
  const Cloud placed = cloud(576, 7);
  std::vector<std::size_t> order(placed.placed.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::vector<std::size_t> shuffled = order;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(3));
  constexpr int kSteps = 5000;
  World reference = box_world(placed, order, 1);
  reference.run(kSteps);
  ASSERT_GT(reference.rebuilds(), 2u);
  ASSERT_GT(reference.touching_pairs(), 200u);
  const auto expected = state_by_id(reference);
  for (const auto& [threads, sphere_order] :
       {std::pair{2, &order}, std::pair{3, &order}, std::pair{1, &shuffled}, std::pair{3, &shuffled}}) {
    World w = box_world(placed, *sphere_order, threads);
    w.run(kSteps);
    EXPECT_EQ(w.threads_in_use(), threads);
    EXPECT_TRUE(same_bits(state_by_id(w), expected)) << threads << " threads, shuffled " << (sphere_order == &shuffled);
    EXPECT_EQ(w.kinetic_energy(), reference.kinetic_energy());
  }
}

TEST(World3D, ClumpsGiveTheSameBitsOnAnyThreadsAndOrder) {
  const Cloud placed = cloud(576, 5);
  std::vector<std::size_t> order(placed.placed.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::vector<std::size_t> shuffled = order;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(9));
  World reference = box_world(placed, order, 1, true);
  reference.run(4000);
  ASSERT_EQ(reference.clumps().size(), 288u);
  ASSERT_GT(reference.touching_pairs(), 100u);
  const auto expected = state_by_id(reference);
  for (const auto& [threads, sphere_order] : {std::pair{2, &order}, std::pair{3, &shuffled}}) {
    World w = box_world(placed, *sphere_order, threads, true);
    w.run(4000);
    EXPECT_TRUE(same_bits(state_by_id(w), expected)) << threads << " threads";
  }
}

// The list holds every pair closer than the skin: checked against all pairs.
TEST(World3D, TheNeighbourListHoldsEveryPairWithinTheSkin) {
  const Cloud placed = cloud(400, 11);
  std::vector<std::size_t> order(placed.placed.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  World w = box_world(placed, order, 1);
  w.refresh();
  std::size_t expected = 0;
  const Spheres& s = w.spheres;
  for (std::size_t a = 0; a < s.size(); ++a)
    for (std::size_t b = a + 1; b < s.size(); ++b) {
      const Vec3 d = s.position(b) - s.position(a);
      const double reach = s.radius[a] + s.radius[b] + w.skin_m();
      expected += dot(d, d) < reach * reach;
    }
  EXPECT_EQ(w.pairs().size(), expected);
}

// A few spheres far from the rest (two of them touching each other) make the
// grid span the middle of the cloud and fall into its edge cells: still every
// pair within the skin, far ones included, and nothing else.
TEST(World3D, EscapedSpheresLoseNoPair) {
  const Cloud placed = cloud(1200, 5);
  World w;
  w.assign(0, 0, w.add_model(ContactModelRegistry::instance().create(
                     "linear", {{"modulus_pa", 1e8}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  for (std::size_t k = 0; k < placed.placed.size(); ++k)
    w.spheres.add_sphere(placed.placed[k].centre, placed.placed[k].radius, 2650, 0, static_cast<std::int64_t>(k));
  const std::vector<Vec3> far = {{1000, 0.01, 0.01}, {1000.0019, 0.01, 0.01}, {-500, -500, 0.01}, {0.01, 0.01, 2000},
                                 {0.0005, 0.0005, -0.003}};
  for (std::size_t k = 0; k < far.size(); ++k) w.spheres.add_sphere(far[k], 0.001, 2650, 0, static_cast<std::int64_t>(5000 + k));
  w.refresh();
  std::set<std::pair<std::uint32_t, std::uint32_t>> expected, listed;
  const Spheres& s = w.spheres;
  for (std::size_t a = 0; a < s.size(); ++a)
    for (std::size_t b = a + 1; b < s.size(); ++b) {
      const Vec3 d = s.position(b) - s.position(a);
      const double reach = s.radius[a] + s.radius[b] + w.skin_m();
      if (dot(d, d) < reach * reach) expected.insert(std::minmax(s.id[a], s.id[b]));
    }
  for (std::size_t k = 0; k < w.pairs().size(); ++k)
    listed.insert(std::minmax(s.id[static_cast<std::size_t>(w.pairs().i[k])], s.id[static_cast<std::size_t>(w.pairs().j[k])]));
  EXPECT_EQ(listed, expected);
  EXPECT_EQ(expected.count({5000u, 5001u}), 1u);  // the far pair is there
}

TEST(World3D, ModelsAreCheckedByTheirOwnRegistry) {
  EXPECT_THROW(ContactModelRegistry::instance().create("parallel_bond", {}, "s.json: contacts.particle-particle"),
               demcal::Error);
  try {
    ContactModelRegistry::instance().create("linear", {{"modulus_pa", 1e9}, {"kn_ks", 1}, {"friction", 0.5}, {"x", 1}},
                                            "s.json: contacts.particle-particle");
    FAIL();
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: contacts.particle-particle"), std::string::npos) << e.what();
  }
}

// A wall switched on after the list was built takes part at once (its pairs are
// made), and two spheres with one id are refused.
TEST(World3D, AWallSwitchedOnCountsAtOnceAndIdsAreUnique) {
  World w;
  w.assign(0, 1, w.add_model(ContactModelRegistry::instance().create(
                     "linear", {{"modulus_pa", 1e8}, {"kn_ks", 1.5}, {"friction", 0.5}}, "test")));
  w.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
  w.walls[0].active = false;
  w.spheres.add_sphere({0, 0, 0.00099}, 0.001, 2650, 0);
  w.refresh();
  EXPECT_EQ(w.wall_pairs().size(), 0u);
  w.walls[0].active = true;
  w.step();
  EXPECT_EQ(w.wall_pairs().size(), 1u);
  EXPECT_GT(w.spheres.vz[0], 0.0);  // pushed up at once
  w.spheres.add_sphere({0.01, 0, 0.002}, 0.001, 2650, 0, 0);  // the id of the first
  EXPECT_THROW(w.refresh(), demcal::Error);
}
