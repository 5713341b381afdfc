// NAME=VALUE options (--set, --target): one parser for every executable.
#include <gtest/gtest.h>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

TEST(NameValue, ParsesAndRejectsWhatIsMissing) {
  auto [name, value] = demcal::parse_name_value("Ec_GPa=16.5", "--set");
  EXPECT_EQ(name, "Ec_GPa");
  EXPECT_DOUBLE_EQ(value, 16.5);
  for (const char* bad : {"Ec_GPa", "=3", "Ec_GPa=", "Ec_GPa=abc"}) {
    try {
      demcal::parse_name_value(bad, "--target");
      FAIL() << bad;
    } catch (const demcal::Error& e) {
      EXPECT_EQ(std::string(e.what()), std::string("--target \"") + bad + "\": expected NAME=VALUE with a number");
    }
  }
}
