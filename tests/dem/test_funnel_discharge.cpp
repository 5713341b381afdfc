// The funnel heap's stages on made-up counts and energies: when the gate
// opens, when the discharge ends (and its flow time), a jam, the settle test,
// and the two ways a run runs out of time.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <utility>

#include "demcal/dem/funnel_discharge.hpp"

namespace {

using demcal::dem::FunnelDischarge;
using demcal::dem::FunnelRun;
using Next = FunnelDischarge::Next;

FunnelRun settings() {
  FunnelRun run;
  run.fill_time_s = 0.1;
  run.jam_time_s = 0.3;
  run.discharged_fraction = 0.75;  // 100 particles: done when 25 are left
  run.settle_kinetic_ratio = 1e-3;
  run.max_time_s = 2;
  return run;
}

FunnelDischarge stages(const FunnelRun& run) {
  return FunnelDischarge(run, 100, {"heap", "heap", "particles", "funnel.outlet_width_m"}, std::chrono::steady_clock::now(),
                         false);
}

TEST(FunnelDischarge, OpensAfterTheFillDischargesThenSettles) {
  FunnelDischarge s = stages(settings());
  std::size_t in_funnel = 100;
  double kinetic = 1, potential = 10;
  int counted = 0, weighed = 0;
  const auto count = [&] { ++counted; return in_funnel; };
  const auto weigh = [&] { ++weighed; return std::pair{kinetic, potential}; };
  EXPECT_EQ(s.check(0.05, count, weigh), Next::step_on);
  EXPECT_EQ(s.check(0.10, count, weigh), Next::open_gate);
  EXPECT_EQ(counted + weighed, 0) << "nothing is counted or weighed while the funnel fills";
  in_funnel = 50;
  EXPECT_EQ(s.check(0.20, count, weigh), Next::step_on);
  in_funnel = 25;  // all but a quarter have left
  EXPECT_EQ(s.check(0.35, count, weigh), Next::step_on);
  EXPECT_DOUBLE_EQ(s.flow_time_s(), 0.35 - 0.10);
  EXPECT_EQ(weighed, 0);
  EXPECT_EQ(s.check(0.40, count, weigh), Next::step_on);  // 0.1 of potential: still moving
  kinetic = 0.005;
  EXPECT_EQ(s.check(0.45, count, weigh), Next::settled);
  EXPECT_DOUBLE_EQ(s.kinetic_over_potential(), 0.0005);
  EXPECT_EQ(counted, 2);
}

TEST(FunnelDischarge, AFunnelNothingLeavesForTheJamTimeHasJammed) {
  FunnelRun run = settings();
  run.fill_time_s = 0.125;  // times that are exact in binary, so the message's numbers are too
  run.jam_time_s = 0.25;
  FunnelDischarge s = stages(run);
  const auto weigh = [] { return std::pair{0.0, 1.0}; };
  std::size_t in_funnel = 100;
  const auto count = [&] { return in_funnel; };
  ASSERT_EQ(s.check(0.125, count, weigh), Next::open_gate);
  in_funnel = 60;
  EXPECT_EQ(s.check(0.25, count, weigh), Next::step_on);  // the last drop, at 0.25 s
  EXPECT_EQ(s.check(0.5, count, weigh), Next::step_on);   // 0.25 s without one: not yet more than jam_time_s
  EXPECT_EQ(s.check(0.625, count, weigh), Next::failed);
  EXPECT_NE(s.reason().find("the funnel jammed: 60 of 100 particles still in it 0.5 s after it opened (none left it "
                            "for run.jam_time_s 0.25 s)"),
            std::string::npos)
      << s.reason();
  EXPECT_NE(s.reason().find("widen funnel.outlet_width_m"), std::string::npos) << s.reason();
  EXPECT_EQ(s.flow_time_s(), -1);
}

TEST(FunnelDischarge, RunningOutOfTimeSaysWhichStageItWasIn) {
  FunnelRun run = settings();
  run.jam_time_s = 10;
  {
    FunnelDischarge s = stages(run);
    std::size_t in_funnel = 100;
    const auto count = [&] { return in_funnel--; };
    const auto weigh = [] { return std::pair{1.0, 1.0}; };
    ASSERT_EQ(s.check(0.1, count, weigh), Next::open_gate);
    EXPECT_EQ(s.check(1.9, count, weigh), Next::step_on);
    EXPECT_EQ(s.check(2.0, count, weigh), Next::failed);
    EXPECT_NE(s.reason().find("had not discharged within run.max_time_s 2 s (99 of 100 particles left)"),
              std::string::npos)
        << s.reason();
  }
  {
    FunnelDischarge s = stages(run);
    std::size_t in_funnel = 0;
    const auto count = [&] { return in_funnel; };
    const auto weigh = [] { return std::pair{0.5, 1.0}; };
    ASSERT_EQ(s.check(0.1, count, weigh), Next::open_gate);
    EXPECT_EQ(s.check(0.2, count, weigh), Next::step_on);
    EXPECT_EQ(s.check(2.0, count, weigh), Next::failed);
    EXPECT_NE(s.reason().find("did not settle within run.max_time_s 2 s (kinetic / potential energy 0.5, asked below 0.001)"),
              std::string::npos)
        << s.reason();
  }
}

TEST(FunnelDischarge, ARunPastItsWallTimeStops) {
  FunnelRun run = settings();
  run.max_wall_s = 1;
  FunnelDischarge s(run, 100, {"heap", "heap_3d", "spheres", "funnel.outlet_diameter_m"},
                    std::chrono::steady_clock::now() - std::chrono::seconds(2), false);
  EXPECT_EQ(s.check(0.0, [] { return std::size_t{100}; }, [] { return std::pair{0.0, 1.0}; }), Next::failed);
  EXPECT_EQ(s.reason(), "timeout: the heap took longer than run.max_wall_s 1 s of wall time");
}

TEST(FunnelDischarge, KeysOutOfRangeNameTheirField) {
  FunnelRun run;
  EXPECT_NO_THROW(run.validate("h.json: run"));
  run.discharged_fraction = 0;
  try {
    run.validate("h.json: run");
    FAIL() << "a discharged fraction of 0 was accepted";
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "h.json: run.discharged_fraction must lie in (0, 1]");
  }
  run = FunnelRun{};
  run.check_every_s = run.max_time_s;
  EXPECT_THROW(run.validate("h.json: run"), std::exception);
}

}  // namespace
