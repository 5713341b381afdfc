// Results keyed by identity, not by array order: the same specimen with its
// disks stored in another order (as a spatial sort or threads would leave
// them) gives the same bits for every disk, bond strengths included.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "../common/load_until_breaks.hpp"
#include "../common/same_bits.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/scene.hpp"

using namespace demcal;
using namespace demcal::dem;

namespace {

// The specimen's disks in the given order (ids = their index in the specimen),
// the scene's contact models, the platens of `like`, bonds keyed by `seed`.
World world_in_order(const Scene& scene, const std::map<std::string, double>& parameters, const Specimen& s,
                     const std::vector<std::size_t>& order, const World& like, std::uint64_t seed) {
  World world(like.settings());
  bind_contact_models(world, scene, parameters);
  for (std::size_t i : order)
    world.bodies.add_disk(s.x[i], s.y[i], s.radius[i], s.density_kg_m3, s.thickness_m, kSpecimenGroup,
                          static_cast<std::int64_t>(i));
  world.walls = like.walls;
  world.install_bonds(0.01 * *std::min_element(s.radius.begin(), s.radius.end()), seed);
  world.make_wall_contacts_force_free();  // as make_platen_world starts them at the vessel's faces
  return world;
}

}  // namespace

TEST(Identity, ReorderedDisksGiveTheSameBitsForEveryDisk) {
  // Contact bonds with normal-distributed strengths (drawn per bond), and parallel bonds.
  for (const char* file : {"tests/data/ucs_rock_cb_small.json", "tests/data/ucs_small.json"}) {
    Scene scene = Scene::load(std::string(DEMCAL_SOURCE_DIR) + "/" + file);
    const auto parameters = scene.resolve({});
    const Specimen s = cached_specimen(specimen_spec(scene, parameters, 3), "");
    World platen = make_platen_world(scene, parameters, s, 3);

    std::vector<std::size_t> in_order(s.size()), shuffled(s.size());
    std::iota(in_order.begin(), in_order.end(), 0);
    shuffled = in_order;
    Rng rng(11);
    rng.shuffle(shuffled);
    ASSERT_NE(shuffled, in_order);
    World a = world_in_order(scene, parameters, s, in_order, platen, 3);
    World b = world_in_order(scene, parameters, s, shuffled, platen, 3);
    // Load until bonds break (their strengths drawn per bond), then as many steps more.
    const std::uint64_t steps = test::load_until_breaks(a, 20);
    ASSERT_GE(a.breaks().size(), 20u) << file << ": the run should reach bond breakage";
    a.run(steps);
    b.run(2 * steps);
    test::expect_same_bits_per_id(a, b);
  }
}

TEST(Identity, ABondsStrengthDependsOnTheSeedAndItsDisksOnly) {
  EXPECT_EQ(keyed_seed(1, 2, 3), keyed_seed(1, 2, 3));
  EXPECT_NE(keyed_seed(1, 2, 3), keyed_seed(1, 3, 2));
  EXPECT_NE(keyed_seed(1, 2, 3), keyed_seed(2, 2, 3));
  EXPECT_NE(keyed_seed(0, 0, 1), keyed_seed(0, 1, 0));
}
