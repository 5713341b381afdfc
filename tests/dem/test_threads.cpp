// One run's force and integration loops on several threads give the same
// bits as on one: each disk adds its pairs' contributions in the serial
// loop's order, and bond breaks are logged in pair order.
#include <gtest/gtest.h>

#include "../common/load_until_breaks.hpp"
#include "../common/same_bits.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/scene.hpp"

using namespace demcal;
using namespace demcal::dem;


TEST(Threads, OneRunOnSeveralThreadsGivesTheSameBitsAsOnOne) {
  // Contact bonds, parallel bonds, and a concrete whose aggregates are clumps.
  for (const char* file :
       {"tests/data/ucs_rock_cb_small.json", "tests/data/ucs_small.json", "tests/data/ucs_concrete_small.json"}) {
    Scene scene = Scene::load(std::string(DEMCAL_SOURCE_DIR) + "/" + file);
    const auto parameters = scene.resolve({});
    const Specimen s = cached_specimen(specimen_spec(scene, parameters, 2), "");
    World serial = make_platen_world(scene, parameters, s, 2);
    serial.settings().threads = 1;
    serial.refresh();
    ASSERT_EQ(serial.threads_in_use(), 1);
    for (int threads : {2, 3}) {
      World threaded = make_platen_world(scene, parameters, s, 2);
      threaded.settings().threads = threads;
      threaded.settings().min_disks_per_thread = 1;  // these specimens are small
      threaded.refresh();
      ASSERT_EQ(threaded.threads_in_use(), threads) << file;
      if (threads == 2) {
        // Load until bonds break, then as many steps more.
        const std::uint64_t steps = test::load_until_breaks(serial, 20);
        ASSERT_GE(serial.breaks().size(), 20u) << file << ": the run should reach bond breakage";
        serial.run(steps);
      }
      threaded.run(serial.steps_done());
      SCOPED_TRACE(std::string(file) + ", " + std::to_string(threads) + " threads");
      test::expect_same_bits(serial, threaded);
    }
  }
}

TEST(Threads, SmallRunsStayOnOneThread) {
  Scene scene = Scene::load(std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json");
  const auto parameters = scene.resolve({});
  const Specimen s = cached_specimen(specimen_spec(scene, parameters, 2), "");
  World world = make_platen_world(scene, parameters, s, 2);
  world.settings().threads = 4;
  world.settings().min_disks_per_thread = world.bodies.size() / 2 + 1;
  world.refresh();
  EXPECT_EQ(world.threads_in_use(), 1);
  world.settings().min_disks_per_thread = world.bodies.size() / 2;
  world.refresh();
  EXPECT_EQ(world.threads_in_use(), 2);
}
