#include <gtest/gtest.h>

#include "demcal/core/log.hpp"
#include "demcal/core/progress.hpp"

TEST(Progress, LineShowsCountPercentAndRate) {
  demcal::log::set_level(demcal::log::Level::Quiet);  // keep the test output clean
  demcal::Progress progress("points", 4);
  progress.set_units_name("particle-steps");
  progress.advance(1, 1e6);
  std::string line = progress.line();
  EXPECT_NE(line.find("points: 1/4 (25%)"), std::string::npos) << line;
  EXPECT_NE(line.find("particle-steps/s"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA"), std::string::npos) << line;
  progress.advance(3);
  EXPECT_NE(progress.line().find("4/4 (100%)"), std::string::npos);
  demcal::log::set_level(demcal::log::Level::Normal);
}

TEST(Progress, DurationsReadAsAPersonWouldWriteThem) {
  EXPECT_EQ(demcal::format_duration(12.34), "12.3s");
  EXPECT_EQ(demcal::format_duration(185), "3m05s");
  EXPECT_EQ(demcal::format_duration(3720), "1h02m");
  EXPECT_EQ(demcal::format_duration(-1), "?");
}

TEST(Progress, ANoteSaysWhatTheLoopIsDoingAtTheLinesEnd) {
  demcal::log::set_level(demcal::log::Level::Quiet);  // keep the test output clean
  demcal::Progress progress("heap", 100);
  progress.advance(10);
  EXPECT_EQ(progress.line().find(';'), std::string::npos) << progress.line();  // no note: no trailing part
  progress.set_note("discharging: 40 of 100 particles out");
  const std::string line = progress.line();
  const std::string tail = "; discharging: 40 of 100 particles out";
  ASSERT_GE(line.size(), tail.size());
  EXPECT_EQ(line.substr(line.size() - tail.size()), tail) << line;
  demcal::log::set_level(demcal::log::Level::Normal);
}
