// A world's checkpoint (World::write_state, read_state): a world built the
// same way takes the state back and steps on with the same bits as the one
// that wrote it; a state of another world is refused.
#include <gtest/gtest.h>

#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "bonded_bodies.hpp"

using namespace demcal::dem;

namespace {

// A bonded hexagonal lattice falling on a floor under gravity, its bonds strong enough to hold: contacts with a
// history (the bonds' forces, the floor's shear) to carry across the checkpoint.
World falling_lattice() {
  WorldSettings settings;
  settings.damping = 0.1;
  settings.gravity_y_m_s2 = -9.81;
  World world(settings);
  world.assign(0, 0, world.add_model(demcal::dem::testing::unbreakable_parallel_bond(1e8, 2.0, 1e8, 2.0)));
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"modulus_pa", 1e8}, {"kn_ks", 2.0}, {"friction", 0.5}}, "test")));
  demcal::dem::testing::add_hexagonal_lattice(world.bodies, 6, 5, 0.01, 1e-4, 2600);
  for (std::size_t i = 0; i < world.bodies.size(); ++i) world.bodies.y[i] += 0.0101;
  Wall floor;
  floor.x0 = -1;
  floor.x1 = 1;
  floor.group = 1;
  world.walls = {floor};
  world.install_bonds(2e-4, 1);
  world.refresh();
  return world;
}

}  // namespace

TEST(WorldState, AWorldTakesItsStateBackAndStepsOnWithTheSameBits) {
  World a = falling_lattice();
  a.run(3000);  // landed: contacts with the floor carry shear history
  std::stringstream saved;
  a.write_state(saved);
  a.refresh();
  a.run(2000);

  World b = falling_lattice();
  b.read_state(saved);
  b.refresh();
  b.run(2000);
  EXPECT_EQ(a.bodies.x, b.bodies.x);
  EXPECT_EQ(a.bodies.y, b.bodies.y);
  EXPECT_EQ(a.bodies.vx, b.bodies.vx);
  EXPECT_EQ(a.bodies.w, b.bodies.w);
  EXPECT_EQ(a.time_s(), b.time_s());
  EXPECT_EQ(a.steps_done(), b.steps_done());
  std::size_t on_floor = 0;  // the checkpoint carried contacts with the floor, not just a fall
  for (std::size_t k = 0; k < a.wall_pairs().size(); ++k) on_floor += (a.wall_pairs().flags[k] & kTouching) != 0;
  EXPECT_GT(on_floor, 0u);
  EXPECT_GT(a.time_s(), 0.0);
}

TEST(WorldState, AStateOfAnotherWorldIsRefused) {
  World a = falling_lattice();
  std::stringstream saved;
  a.write_state(saved);
  World smaller;
  smaller.assign(0, 0, smaller.add_model(demcal::dem::testing::unbreakable_parallel_bond(1e8, 2.0, 1e8, 2.0)));
  smaller.bodies.add_disk(0, 0, 0.01, 2600, 1, 0);
  smaller.refresh();
  try {
    smaller.read_state(saved);
    FAIL() << "a state of 30 disks was taken by a world of 1";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("world state: 30 disks, this world has 1"), std::string::npos) << e.what();
  }
  std::stringstream garbage("not a state at all");
  EXPECT_THROW(a.read_state(garbage), demcal::Error);
}
