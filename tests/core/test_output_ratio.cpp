// Ratio outputs A/B: parsed strictly, formed row by row (per run), looked up
// beside plain outputs, and kept out of HDF5 names.
#include <gtest/gtest.h>

#include "../common/scratch.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/output_ratio.hpp"

using namespace demcal;

TEST(OutputRatio, ParsesAOverBAndRefusesHalfRatios) {
  EXPECT_FALSE(parse_output_ratio("sigma_u_MPa", "w"));
  const auto r = parse_output_ratio("sigma_t_MPa/sigma_u_MPa", "w");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->numerator, "sigma_t_MPa");
  EXPECT_EQ(r->denominator, "sigma_u_MPa");
  for (const char* bad : {"a/", "/b", "a/b/c"}) {
    try {
      parse_output_ratio(bad, "study.json: targets");
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("study.json: targets: \"" + std::string(bad) + "\" is not an output or a ratio"),
                std::string::npos);
    }
  }
}

TEST(OutputRatio, ColumnsAreFormedRunByRun) {
  Table t;
  t.add_column("a", {2, 9, 10});
  t.add_column("b", {4, 3, 5});
  add_ratio_columns(t, {"a", "a/b", "b/a"}, "data.csv");
  EXPECT_EQ(t.column("a/b"), (std::vector<double>{0.5, 3, 2}));
  EXPECT_EQ(t.column("b/a"), (std::vector<double>{2, 1.0 / 3.0, 0.5}));
  EXPECT_THROW(add_ratio_columns(t, {"a/c"}, "data.csv"), Error);
  EXPECT_THROW(t.write_hdf5(demcal::test::scratch_path("ratio.h5"), "/t"), Error);
}

TEST(OutputRatio, ValuesAreLookedUpBesidePlainOutputs) {
  const std::map<std::string, double> macro = {{"sigma_t_MPa", 6}, {"sigma_u_MPa", 60}};
  double v = 0;
  ASSERT_TRUE(output_value(macro, "sigma_t_MPa/sigma_u_MPa", v));
  EXPECT_DOUBLE_EQ(v, 0.1);
  ASSERT_TRUE(output_value(macro, "sigma_u_MPa", v));
  EXPECT_DOUBLE_EQ(v, 60);
  EXPECT_FALSE(output_value(macro, "E_GPa", v));
  EXPECT_FALSE(output_value(macro, "sigma_t_MPa/E_GPa", v));
}
