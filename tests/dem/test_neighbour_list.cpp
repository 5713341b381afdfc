// The cell-grid neighbour list finds exactly the pairs a brute-force search
// finds, keeps contact state across rebuilds, and rebuilds only when needed.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <algorithm>
#include <set>
#include <utility>
#include <string>
#include <tuple>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"

using namespace demcal::dem;

namespace {

std::unique_ptr<ContactModel> linear() {
  return ContactModelRegistry::instance().create("linear", {{"modulus_pa", 1e8}, {"kn_ks", 2.0}, {"friction", 0.5}},
                                                 "test");
}

World random_world(std::size_t n, std::uint64_t seed, double skin) {
  WorldSettings settings;
  settings.skin_m = skin;
  World world(settings);
  world.assign(0, 0, world.add_model(linear()));
  world.assign(0, 1, world.add_model(linear()));  // a second model for group-1 disks
  world.assign(1, 1, 0);
  demcal::Rng rng(seed);
  for (std::size_t k = 0; k < n; ++k)
    world.bodies.add_disk(rng.uniform(0, 0.05), rng.uniform(0, 0.03), rng.uniform(4e-4, 1e-3), 2000, 1, rng.below(2));
  return world;
}

std::set<std::pair<int, int>> brute_force(const World& world, double skin) {
  std::set<std::pair<int, int>> pairs;
  const Bodies& b = world.bodies;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = i + 1; j < b.size(); ++j) {
      double reach = b.radius[i] + b.radius[j] + skin;
      if (std::hypot(b.x[j] - b.x[i], b.y[j] - b.y[i]) < reach) pairs.insert({int(i), int(j)});
    }
  return pairs;
}

}  // namespace

TEST(NeighbourList, FindsExactlyTheBruteForcePairs) {
  for (std::uint64_t seed : {1, 2, 3}) {
    World world = random_world(600, seed, 2e-4);
    world.refresh();
    std::set<std::pair<int, int>> found;
    for (std::size_t k = 0; k < world.pairs().size(); ++k) {
      EXPECT_LT(world.pairs().i[k], world.pairs().j[k]);
      found.insert({world.pairs().i[k], world.pairs().j[k]});
    }
    EXPECT_EQ(found.size(), world.pairs().size()) << "no pair twice";
    EXPECT_EQ(found, brute_force(world, 2e-4));
    // Pairs of one model form one contiguous run.
    for (std::size_t k = 1; k < world.pairs().size(); ++k) EXPECT_LE(world.pairs().model[k - 1], world.pairs().model[k]);
  }
}

// The grid search on several threads (each a band of cell rows, used from
// the second build on, once the world knows its threads) finds the same
// pairs, in (model, id i, id j) order, each once.
TEST(NeighbourList, FindsTheBruteForcePairsInOrderOnSeveralThreads) {
  for (const int threads : {2, 3}) {
    World world = random_world(600, 4, 2e-4);
    world.settings().threads = threads;
    world.settings().min_disks_per_thread = 1;
    world.refresh();
    ASSERT_EQ(world.threads_in_use(), threads);
    world.refresh();
    const ContactSet& pairs = world.pairs();
    std::set<std::pair<int, int>> found;
    for (std::size_t k = 0; k < pairs.size(); ++k) found.insert({pairs.i[k], pairs.j[k]});
    EXPECT_EQ(found, brute_force(world, 2e-4)) << threads << " threads";
    EXPECT_EQ(found.size(), pairs.size()) << "no pair twice";
    for (std::size_t k = 1; k < pairs.size(); ++k)
      EXPECT_LT(std::make_tuple(pairs.model[k - 1], pairs.i[k - 1], pairs.j[k - 1]),
                std::make_tuple(pairs.model[k], pairs.i[k], pairs.j[k]))
          << "pair " << k;
  }
}

TEST(NeighbourList, EveryDeclaredStateColumnSurvivesARebuild) {
  World world = random_world(300, 4, 2e-4);
  world.refresh();
  ContactSet& pairs = world.pairs();
  // A distinct value in every column each pair's model declares.
  auto value = [&](std::size_t k, std::size_t c) {
    return 1.0 + static_cast<double>(pairs.i[k]) * 1e-3 + pairs.j[k] + 1e4 * static_cast<double>(c);
  };
  std::size_t columns_seen = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::size_t columns = world.model(pairs.model[k]).state_columns().size();
    for (std::size_t c = 0; c < columns; ++c) pairs.state(k, c) = value(k, c);
    columns_seen = std::max(columns_seen, columns);
  }
  ASSERT_GE(columns_seen, 4u);
  auto i_before = pairs.i, j_before = pairs.j;
  world.refresh();
  ASSERT_EQ(world.pairs().size(), i_before.size());
  for (std::size_t k = 0; k < i_before.size(); ++k) {
    EXPECT_EQ(world.pairs().i[k], i_before[k]);
    EXPECT_EQ(world.pairs().j[k], j_before[k]);
    const std::size_t columns = world.model(pairs.model[k]).state_columns().size();
    for (std::size_t c = 0; c < columns; ++c) EXPECT_EQ(world.pairs().state(k, c), value(k, c)) << "column " << c;
  }
  // By name, through the world: the linear model's shear force is column 3.
  EXPECT_EQ(world.pair_state(0, "shear_force_n"), value(0, 3));
  EXPECT_THROW(world.pair_state(0, "bond_moment_nm"), demcal::Error);
}

TEST(NeighbourList, RebuildsOnlyAfterHalfTheSkinIsUsed) {
  WorldSettings settings;
  settings.skin_m = 1e-4;
  settings.damping = 0;
  World world(settings);
  world.assign(0, 0, world.add_model(linear()));
  world.bodies.add_disk(0, 0, 1e-3, 2000, 1, 0);
  world.bodies.add_disk(0.01, 0, 1e-3, 2000, 1, 0);
  world.bodies.vx[0] = 1.0;  // moves 1 m/s: half the skin (5e-5 m) takes 5e-5 s
  world.step();
  std::uint64_t first = world.rebuilds();
  double dt = world.dt_s();
  world.run(static_cast<std::uint64_t>(4e-5 / dt));
  EXPECT_EQ(world.rebuilds(), first);
  world.run(static_cast<std::uint64_t>(2e-5 / dt) + 2);
  EXPECT_EQ(world.rebuilds(), first + 1);
}

// assign_blocks makes at once what add() makes pair by pair; a set given its
// layout again is empty and takes new blocks of any size.
TEST(ContactSet, AssignBlocksMatchesAddingPairByPair) {
  ContactSet added, assigned;
  for (ContactSet* set : {&added, &assigned}) set->set_layout({2, 0, 3});
  for (int k = 0; k < 3; ++k) added.add(k, k + 1, 0);
  for (int k = 0; k < 2; ++k) added.add(k, k + 2, 2);
  assigned.assign_blocks({3, 0, 2});
  ASSERT_EQ(assigned.size(), added.size());
  for (std::size_t k = 0; k < added.size(); ++k) {
    assigned.i[k] = added.i[k];
    assigned.j[k] = added.j[k];
    EXPECT_EQ(assigned.model[k], added.model[k]);
    EXPECT_EQ(assigned.flags[k], 0);
  }
  for (std::uint8_t m : {0, 1, 2}) {
    EXPECT_EQ(assigned.begin(m), added.begin(m)) << int(m);
    EXPECT_EQ(assigned.end(m), added.end(m)) << int(m);
  }
  assigned.state(4, 2) = 7.0;
  assigned.set_layout({2, 0, 3});
  EXPECT_EQ(assigned.size(), 0u);
  assigned.assign_blocks({0, 0, 5});
  EXPECT_EQ(assigned.begin(2), 0u);
  for (std::size_t k = 0; k < 5; ++k)
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(assigned.state(k, c), 0.0) << k << " " << c;
  EXPECT_THROW(assigned.assign_blocks({0, 0, 0, 1}), demcal::Error);
}

// The state is stored column by column, each column as long as the block's
// capacity: adding pairs one by one regrows every column, and a copy between
// sets of other capacities takes each column of the pair.
TEST(ContactSet, StateKeepsEveryColumnAsTheBlockGrows) {
  ContactSet grown, copied;
  grown.set_layout({3, 4});
  constexpr int kPairs = 40;  // past capacities 16 and 32
  auto value = [](int k, std::size_t c) { return 100.0 * k + static_cast<double>(c) + 0.5; };
  for (int k = 0; k < 3; ++k) grown.add(k, k + 1, 0);
  for (int k = 0; k < kPairs; ++k) {
    const std::size_t at = grown.add(k, k + 2, 1);
    for (std::size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(grown.state(at, c), 0.0) << k << " " << c;  // a new pair starts at zero
      grown.state(at, c) = value(k, c);
    }
  }
  const ConstPairBlock block = std::as_const(grown).block(1);
  ASSERT_EQ(block.size, static_cast<std::size_t>(kPairs));
  for (int k = 0; k < kPairs; ++k)
    for (std::size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(grown.state(3 + static_cast<std::size_t>(k), c), value(k, c)) << k << " " << c;
      EXPECT_EQ(block.column[c][static_cast<std::size_t>(k)], value(k, c)) << k << " " << c;
      EXPECT_EQ(block.column(c, static_cast<std::size_t>(k)), value(k, c)) << k << " " << c;
    }
  copied.set_layout({3, 4});
  copied.assign_blocks({0, kPairs});
  for (int k = 0; k < kPairs; ++k)
    copied.copy_state(static_cast<std::size_t>(kPairs - 1 - k), grown, 3 + static_cast<std::size_t>(k));
  for (int k = 0; k < kPairs; ++k)
    for (std::size_t c = 0; c < 4; ++c)
      EXPECT_EQ(copied.state(static_cast<std::size_t>(kPairs - 1 - k), c), value(k, c)) << k << " " << c;
}

TEST(ContactModels, RegistryNamesModelsAndRejectsBadParameters) {
  auto& registry = ContactModelRegistry::instance();
  const std::vector<std::string> names = registry.names();
  EXPECT_NE(std::find(names.begin(), names.end(), "linear"), names.end());
  EXPECT_THROW(registry.create("hertz", {}, "scene.json"), demcal::Error);
  EXPECT_THROW(registry.create("linear", {{"modulus_pa", 0.0}, {"kn_ks", 2.0}, {"friction", 0.5}}, "s"), demcal::Error);
  EXPECT_THROW(registry.create("linear", {{"modulus_pa", -1e9}, {"kn_ks", 2.0}, {"friction", 0.5}}, "s"), demcal::Error);
  EXPECT_THROW(registry.create("linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.0}}, "s"), demcal::Error);
  EXPECT_THROW(registry.create("linear", {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}, {"fricton", 1}}, "s"),
               demcal::Error);
  try {
    registry.create("linear", {{"modulus_pa", 1e9}, {"kn_ks", -2.0}, {"friction", 0.5}}, "scene.json: mortar");
    FAIL() << "expected an error";
  } catch (const demcal::Error& e) {
    EXPECT_EQ(std::string(e.what()), "scene.json: mortar: kn_ks must be positive (got -2)");
  }
}

TEST(ContactModels, PairsWithoutAModelAreAnError) {
  World world;
  world.add_model(linear());
  world.bodies.add_disk(0, 0, 1e-3, 2000, 1, 0);
  world.bodies.add_disk(1.5e-3, 0, 1e-3, 2000, 1, 3);
  EXPECT_THROW(world.refresh(), demcal::Error);
}

TEST(ContactModels, PairsWithoutAModelAreAnErrorOnThreadsToo) {
  World world = random_world(600, 5, 2e-4);
  world.settings().threads = 2;
  world.settings().min_disks_per_thread = 1;
  world.refresh();
  ASSERT_EQ(world.threads_in_use(), 2);
  world.bodies.group[300] = 3;  // no model for groups 3 and 0 or 1
  try {
    world.refresh();
    FAIL() << "expected an error";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no contact model assigned to material groups"), std::string::npos)
        << e.what();
  }
}
