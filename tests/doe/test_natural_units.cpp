#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/core/table.hpp"
#include "demcal/doe/natural_units.hpp"
#include "demcal/doe/orthogonal_array.hpp"
#include "demcal/doe/response_surface.hpp"
#include "demcal/doe/space_filling.hpp"

using namespace demcal;
using namespace demcal::doe;

namespace {

std::string data_path(const std::string& relative) { return std::string(DEMCAL_SOURCE_DIR) + "/data/" + relative; }

// Rows of `columns` from a table, rounded to 3 decimals and sorted, so two
// designs compare as multisets of points whatever their run order.
std::vector<std::vector<double>> point_set(const Table& table, const std::vector<std::string>& columns) {
  std::vector<std::vector<double>> points(table.rows());
  for (std::size_t i = 0; i < table.rows(); ++i)
    for (const auto& c : columns) points[i].push_back(std::round(table.at(i, c) * 1000.0) / 1000.0);
  std::sort(points.begin(), points.end());
  return points;
}

}  // namespace

TEST(NaturalUnits, ConcreteStudyCcdMatchesThePublishedRuns) {
  ParameterSpace space = ParameterSpace::load(data_path("spaces/su2021_ccd_sigma_u.json"));
  CcdOptions options;
  options.factors = 2;
  Design d = central_composite(options);
  name_factors(d, space);
  Table ours = design_table(d, &space);
  Table published = Table::read_csv(data_path("literature/su2021_CCD2_sigma_u.csv"));
  std::vector<std::string> names = {"pb_sigma_c_MPa", "pb_tau_c_MPa"};
  EXPECT_EQ(point_set(ours, names), point_set(published, names));
}

TEST(NaturalUnits, ConcreteStudyBoxBehnkenDesignsMatchThePublishedRuns) {
  struct Case { const char* space; const char* published; int factors; };
  for (Case c : {Case{"spaces/su2021_bbd_E.json", "literature/su2021_BBD5_E.csv", 5},
                 Case{"spaces/su2021_bbd_nu.json", "literature/su2021_BBD4_nu.csv", 4}}) {
    ParameterSpace space = ParameterSpace::load(data_path(c.space));
    Design d = box_behnken(c.factors);
    name_factors(d, space);
    Table ours = design_table(d, &space);
    Table published = Table::read_csv(data_path(c.published));
    std::vector<std::string> names;
    for (const auto& p : space.parameters()) names.push_back(p.name);
    EXPECT_EQ(point_set(ours, names), point_set(published, names)) << c.published;
  }
}

TEST(NaturalUnits, ConcreteStudyL64UsesTheListedLevelsWithPublishedFrequencies) {
  ParameterSpace space = ParameterSpace::load(data_path("spaces/su2021_concrete.json"));
  OaRequest request;
  request.runs = 64;
  request.levels = {{3, 13}};
  request.blanks = 1;
  Design d = orthogonal_array(request);
  d.blank[13] = true;
  name_factors(d, space);
  Table ours = design_table(d, &space);
  Table published = Table::read_csv(data_path("literature/su2021_L64_orthogonal.csv"));
  for (const auto& p : space.parameters()) {
    // Same levels at the same frequencies (32 at the lowest, 16 at the others).
    std::vector<double> a = ours.column(p.name), b = published.column(p.name);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << p.name;
  }
  EXPECT_TRUE(ours.has_column("blank1"));
  EXPECT_TRUE(ours.has_column("Ec_GPa_coded"));
  EXPECT_EQ(ours.attributes().at("blank_columns"), "blank1");
}

TEST(NaturalUnits, UnitCodedDesignsFillTheBounds) {
  ParameterSpace space = ParameterSpace::from_json(nlohmann::json::parse(R"({"parameters": [
      {"name": "a", "low": 2, "high": 4}, {"name": "b", "low": 1e-4, "high": 1e-2, "log_scale": true}]})"), "inline");
  LhsOptions options;
  options.runs = 50;
  options.factors = 2;
  Design d = latin_hypercube(options);
  name_factors(d, space);
  Table t = design_table(d, &space);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    EXPECT_GE(t.at(i, "a"), 2.0);
    EXPECT_LE(t.at(i, "a"), 4.0);
    EXPECT_NEAR(t.at(i, "a"), 2.0 + 2.0 * t.at(i, "a_coded"), 1e-12);
    EXPECT_NEAR(std::log10(t.at(i, "b")), -4.0 + 2.0 * t.at(i, "b_coded"), 1e-12);
  }
}

TEST(NaturalUnits, MismatchedLevelCountsAndFactorCountsAreErrors) {
  ParameterSpace space = ParameterSpace::load(data_path("spaces/su2021_ccd_sigma_u.json"));
  OaRequest request;
  request.runs = 4;
  request.levels = {{2, 2}};
  Design two_level = orthogonal_array(request);
  name_factors(two_level, space);
  EXPECT_THROW(design_table(two_level, &space), Error);  // the space lists 3 levels
  Design three = box_behnken(3);
  EXPECT_THROW(name_factors(three, space), Error);
}
