#include <gtest/gtest.h>

#include "../common/error_of.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/parameter_space.hpp"

using demcal::Error;
using demcal::ParameterSpace;
using nlohmann::json;

using demcal::test::error_of;

namespace {

json valid_space() {
  return json::parse(R"({
    "parameters": [
      {"name": "Ec_GPa", "unit": "GPa", "low": 10, "high": 30, "levels": [10, 20, 30], "reference": 16},
      {"name": "R_min_m", "unit": "m", "low": 1e-4, "high": 1e-3, "log_scale": true}
    ],
    "fixed": {"density_kg_m3": 2397},
    "tied": [{"name": "pb_Ec_GPa", "source": "Ec_GPa", "factor": 1.0}]
  })");
}


}  // namespace

TEST(ParameterSpace, ReadsParametersFixedAndTied) {
  ParameterSpace space = ParameterSpace::from_json(valid_space(), "space.json");
  ASSERT_EQ(space.size(), 2u);
  EXPECT_EQ(space.parameters()[0].name, "Ec_GPa");
  EXPECT_EQ(space.parameters()[0].levels.size(), 3u);
  EXPECT_DOUBLE_EQ(*space.parameters()[0].reference, 16.0);
  EXPECT_TRUE(space.parameters()[1].log_scale);
  EXPECT_EQ(space.index_of("R_min_m"), 1u);
  auto values = space.complete({20.0, 5e-4});
  EXPECT_DOUBLE_EQ(values.at("pb_Ec_GPa"), 20.0);
  EXPECT_DOUBLE_EQ(values.at("density_kg_m3"), 2397.0);
}

TEST(ParameterSpace, CodedToNaturalUnits) {
  ParameterSpace space = ParameterSpace::from_json(valid_space(), "space.json");
  const auto& ec = space.parameters()[0];
  EXPECT_DOUBLE_EQ(ec.from_symmetric(-1), 10.0);
  EXPECT_DOUBLE_EQ(ec.from_symmetric(0), 20.0);
  EXPECT_DOUBLE_EQ(ec.from_symmetric(1.414213562373095), 20.0 + 14.14213562373095);
  EXPECT_DOUBLE_EQ(ec.from_unit(0.25), 15.0);
  EXPECT_NEAR(ec.to_symmetric(25.0), 0.5, 1e-15);
  const auto& r = space.parameters()[1];  // log scale: the centre is the geometric mean
  EXPECT_NEAR(r.from_symmetric(0), std::sqrt(1e-4 * 1e-3), 1e-15);
  EXPECT_NEAR(r.from_unit(1.0), 1e-3, 1e-15);
}

TEST(ParameterSpace, RoundTripThroughJson) {
  ParameterSpace space = ParameterSpace::from_json(valid_space(), "space.json");
  ParameterSpace again = ParameterSpace::from_json(space.to_json(), "again");
  EXPECT_EQ(again.to_json(), space.to_json());
}

TEST(ParameterSpace, ErrorsNameTheFileFieldAndValue) {
  json low_high = valid_space();
  low_high["parameters"][0]["low"] = 30;
  low_high["parameters"][0]["high"] = 10;
  EXPECT_EQ(error_of([&] { ParameterSpace::from_json(low_high, "s.json"); }),
            "s.json: parameters[0] (\"Ec_GPa\"): low (30) must be below high (10)");

  json unknown = valid_space();
  unknown["parameters"][1]["hihg"] = 3;
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(unknown, "s.json"); }).find("unknown field \"hihg\""), std::string::npos);

  json level_out = valid_space();
  level_out["parameters"][0]["levels"] = {10, 20, 40};
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(level_out, "s.json"); }).find("levels[2] = 40 lies outside [10, 30]"),
            std::string::npos);

  json duplicate = valid_space();
  duplicate["fixed"]["Ec_GPa"] = 3;
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(duplicate, "s.json"); }).find("defined twice"), std::string::npos);

  json bad_tie = valid_space();
  bad_tie["tied"][0]["source"] = "nope";
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(bad_tie, "s.json"); }).find("source \"nope\""), std::string::npos);

  json log_negative = valid_space();
  log_negative["parameters"][1]["low"] = 0;
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(log_negative, "s.json"); }).find("log_scale needs low > 0"),
            std::string::npos);

  json not_number = valid_space();
  not_number["parameters"][0]["high"] = "30";
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(not_number, "s.json"); }).find("\"high\" must be a number"),
            std::string::npos);

  EXPECT_EQ(error_of([] { ParameterSpace::load("/nonexistent/space.json"); }),
            "/nonexistent/space.json: cannot open parameter space file");
  EXPECT_NE(error_of([&] { ParameterSpace::from_json(valid_space(), "s").index_of("E"); }).find("known: Ec_GPa, R_min_m"),
            std::string::npos);
}

TEST(ParameterSpace, RejectsNonFiniteValuesInARun) {
  ParameterSpace space = ParameterSpace::from_json(valid_space(), "space.json");
  EXPECT_THROW(space.complete({std::nan(""), 1e-4}), Error);
  EXPECT_THROW(space.complete({20.0}), Error);
}

TEST(ParameterSpace, SubsetFixesTheRest) {
  ParameterSpace space = ParameterSpace::from_json(valid_space(), "space.json");
  ParameterSpace kept = space.subset({"Ec_GPa"}, {{"R_min_m", 2e-4}});
  EXPECT_EQ(kept.size(), 1u);
  EXPECT_DOUBLE_EQ(kept.fixed().at("R_min_m"), 2e-4);
  // R_min_m has no reference, so dropping it without a value is an error.
  EXPECT_THROW(space.subset({"Ec_GPa"}, {}), Error);
}

TEST(ParameterSpace, ShippedSpacesLoad) {
  for (const char* name : {"su2021_concrete", "su2021_ccd_sigma_u", "su2021_bbd_E", "su2021_bbd_nu"}) {
    ParameterSpace space = ParameterSpace::load(std::string(DEMCAL_SOURCE_DIR) + "/data/spaces/" + name + ".json");
    EXPECT_GE(space.size(), 2u) << name;
    // Every study parameter is fixed or varied: 13 in all.
    EXPECT_EQ(space.size() + space.fixed().size(), 13u) << name;
  }
}
