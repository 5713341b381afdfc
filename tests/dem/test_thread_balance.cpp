// The cuts between a threaded run's parts follow the threads' measured
// speeds, and wherever they fall the run keeps the serial run's bits.
#include <gtest/gtest.h>

#include <stdexcept>

#include "../common/load_until_breaks.hpp"
#include "../common/same_bits.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/thread_balance.hpp"

using namespace demcal;
using namespace demcal::dem;

TEST(ThreadBalance, TimesWithinThreePercentLeaveTheCuts) {
  std::vector<double> cuts = equal_cuts(2);
  EXPECT_FALSE(rebalance_cuts(cuts, {1.0, 1.0}));
  EXPECT_FALSE(rebalance_cuts(cuts, {1.0, 1.029}));
  EXPECT_FALSE(rebalance_cuts(cuts, {0.0, 1.0}));  // a thread that did not run
  EXPECT_EQ(cuts, (std::vector<double>{0.0, 0.5, 1.0}));
}

TEST(ThreadBalance, ASlowerThreadGetsLessHalfwayAtATime) {
  // Thread 0 took twice as long on the same share: the even split is 1/3,
  // 2/3, and one window moves halfway there.
  std::vector<double> cuts = equal_cuts(2);
  ASSERT_TRUE(rebalance_cuts(cuts, {2.0, 1.0}));
  EXPECT_NEAR(cuts[1], 0.5 * (0.5 + 1.0 / 3.0), 1e-15);
  EXPECT_EQ(cuts[0], 0.0);
  EXPECT_EQ(cuts[2], 1.0);
}

TEST(ThreadBalance, CutsConvergeToTheThreadsSpeeds) {
  // Threads doing 1, 2 and 3 units of work per second: after some windows
  // each thread's part is its speed's share and their times agree.
  const std::vector<double> speed = {1.0, 2.0, 3.0};
  std::vector<double> cuts = equal_cuts(3);
  for (int window = 0; window < 40; ++window) {
    std::vector<double> busy(3);
    for (std::size_t t = 0; t < 3; ++t) busy[t] = (cuts[t + 1] - cuts[t]) / speed[t];
    rebalance_cuts(cuts, busy);
  }
  EXPECT_NEAR(cuts[1], 1.0 / 6.0, 0.01);
  EXPECT_NEAR(cuts[2], 3.0 / 6.0, 0.01);
}

TEST(ThreadBalance, NoPartFallsBelowAQuarterOfAnEqualShare) {
  // A thread a thousand times slower (stopped by the system, say) keeps a
  // quarter of its equal share; the others share the rest in proportion.
  std::vector<double> cuts = equal_cuts(4);
  for (int window = 0; window < 30; ++window) {
    std::vector<double> busy = {1000.0 * (cuts[1] - cuts[0]), cuts[2] - cuts[1], cuts[3] - cuts[2],
                                2.0 * (cuts[4] - cuts[3])};
    rebalance_cuts(cuts, busy);
    for (std::size_t t = 0; t < 4; ++t) ASSERT_GE(cuts[t + 1] - cuts[t], 0.0625 - 1e-15) << "window " << window;
  }
  EXPECT_NEAR(cuts[1], 0.0625, 1e-12);
  // The other three: speeds 1, 1, 1/2 share 0.9375 as 2 : 2 : 1.
  EXPECT_NEAR(cuts[2] - cuts[1], 0.375, 0.01);
  EXPECT_NEAR(cuts[4] - cuts[3], 0.1875, 0.01);
}

TEST(ThreadBalance, UnequalAndMovingCutsKeepTheSerialBits) {
  Scene scene = Scene::load(std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json");
  const auto parameters = scene.resolve({});
  const Specimen s = cached_specimen(specimen_spec(scene, parameters, 2), "");
  World serial = make_platen_world(scene, parameters, s, 2);
  serial.settings().threads = 1;
  serial.refresh();
  const std::uint64_t steps = test::load_until_breaks(serial, 20);
  ASSERT_GE(serial.breaks().size(), 20u);
  serial.run(steps);

  struct Case {
    int threads;
    std::vector<double> cuts;  // empty: equal, then moved by the timings every step
  };
  for (const Case& c : {Case{2, {0.0, 0.15, 1.0}}, Case{3, {0.0, 0.6, 0.7, 1.0}}, Case{2, {}}}) {
    World threaded = make_platen_world(scene, parameters, s, 2);
    threaded.settings().threads = c.threads;
    threaded.settings().min_disks_per_thread = 1;
    threaded.settings().thread_balance_every_steps = c.cuts.empty() ? 1 : 0;
    if (!c.cuts.empty()) threaded.set_thread_cuts(c.cuts);
    threaded.refresh();
    ASSERT_EQ(threaded.threads_in_use(), c.threads);
    threaded.run(serial.steps_done());
    SCOPED_TRACE(std::to_string(c.threads) + " threads" + (c.cuts.empty() ? ", cuts moved every step" : ""));
    if (!c.cuts.empty()) {
      EXPECT_EQ(threaded.thread_cuts(), c.cuts);  // held: balancing off
    }
    test::expect_same_bits(serial, threaded);
  }
}

TEST(ThreadBalance, CutsThatAreNotIncreasingFromZeroToOneAreRefused) {
  World world;
  EXPECT_THROW(world.set_thread_cuts({0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(world.set_thread_cuts({0.0, 0.6, 0.5, 1.0}), std::invalid_argument);
  EXPECT_THROW(world.set_thread_cuts({0.1, 0.5, 1.0}), std::invalid_argument);
  EXPECT_THROW(world.set_thread_cuts({0.0, 0.5, 0.9}), std::invalid_argument);
  EXPECT_NO_THROW(world.set_thread_cuts({0.0, 0.3, 1.0}));
}
