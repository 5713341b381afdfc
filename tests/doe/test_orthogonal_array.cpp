#include <gtest/gtest.h>

#include "demcal/core/error.hpp"
#include "demcal/doe/orthogonal_array.hpp"
#include "demcal/doe/properties.hpp"
#include "oa_checks.hpp"

using namespace demcal::doe;
using demcal::doe::testing::has_proportional_frequencies;
using demcal::doe::testing::is_strength_two;

TEST(RaoHamming, StrengthTwoWithTheRightShape) {
  for (auto [q, m] : std::vector<std::pair<int, int>>{{2, 2}, {2, 3}, {2, 4}, {2, 5}, {3, 2}, {3, 3}, {3, 4},
                                                      {4, 2}, {4, 3}, {5, 2}, {5, 3}, {7, 2}, {8, 2}, {9, 2}}) {
    LevelMatrix a = rao_hamming(q, m);
    int rows = 1;
    for (int k = 0; k < m; ++k) rows *= q;
    EXPECT_EQ(a.rows(), rows);
    EXPECT_EQ(a.cols(), (rows - 1) / (q - 1));
    EXPECT_TRUE(is_strength_two(a)) << "q=" << q << " m=" << m;
  }
}

TEST(RaoHamming, L8ColumnsAreTaguchis) {
  // L8: A, B, AB, C, AC, BC, ABC with levels 0/1 (interaction = sum mod 2).
  LevelMatrix a = rao_hamming(2, 3);
  for (int r = 0; r < 8; ++r) {
    int A = a(r, 0), B = a(r, 1), C = a(r, 3);
    EXPECT_EQ(a(r, 2), A ^ B);
    EXPECT_EQ(a(r, 4), A ^ C);
    EXPECT_EQ(a(r, 5), B ^ C);
    EXPECT_EQ(a(r, 6), A ^ B ^ C);
  }
  EXPECT_EQ(a.row(0).sum(), 0);  // first run at the first level everywhere
}

TEST(Bose, StrengthTwo) {
  for (int q : {2, 3, 4, 5, 7, 8, 9, 11}) {
    LevelMatrix a = bose(q);
    EXPECT_EQ(a.rows(), q * q);
    EXPECT_EQ(a.cols(), q + 1);
    EXPECT_TRUE(is_strength_two(a)) << q;
  }
}

TEST(AddelmanKempthorne, StrengthTwo) {
  for (int q : {3, 5, 7, 9}) {
    LevelMatrix a = addelman_kempthorne(q);
    EXPECT_EQ(a.rows(), 2 * q * q);
    EXPECT_EQ(a.cols(), 2 * q + 1);
    EXPECT_TRUE(is_strength_two(a)) << q;
  }
  EXPECT_THROW(addelman_kempthorne(4), demcal::Error);
}

TEST(MixedArrays, L18AndL36AreStrengthTwo) {
  LevelMatrix a18 = l18();
  EXPECT_EQ(a18.rows(), 18);
  EXPECT_EQ(a18.cols(), 8);
  EXPECT_EQ(a18.col(0).maxCoeff(), 1);
  EXPECT_TRUE(is_strength_two(a18));
  LevelMatrix a36 = l36();
  EXPECT_EQ(a36.rows(), 36);
  EXPECT_EQ(a36.cols(), 23);
  for (int j = 0; j < 11; ++j) EXPECT_EQ(a36.col(j).maxCoeff(), 1);
  for (int j = 11; j < 23; ++j) EXPECT_EQ(a36.col(j).maxCoeff(), 2);
  EXPECT_TRUE(is_strength_two(a36));
  // No duplicated runs in either.
  EXPECT_EQ(analyse(design_from_levels(a18, std::vector<int>(8, 3), "oa", "")).duplicate_runs, 0);
}

TEST(CollapsedL64, FrequenciesAre32_16_16AndMainEffectsStayOrthogonal) {
  LevelMatrix full = rao_hamming(4, 3);
  ASSERT_EQ(full.cols(), 21);
  for (int onto = 0; onto < 3; ++onto) {
    LevelMatrix a = collapse_levels(full, 3, onto);
    Eigen::MatrixXd x = a.cast<double>();
    EXPECT_TRUE(has_proportional_frequencies(x)) << "onto " << onto;
    for (int j = 0; j < 21; ++j)
      for (int level = 0; level < 3; ++level)
        EXPECT_EQ((a.col(j).array() == level).count(), level == onto ? 32 : 16);
    EXPECT_FALSE(is_strength_two(a));  // unequal frequencies: not an OA
  }
}

TEST(OrthogonalArrayRequest, The64RunPlanOfTheConcreteStudy) {
  OaRequest request;
  request.runs = 64;
  request.levels = {{3, 13}};
  request.blanks = 1;
  Design d = orthogonal_array(request);
  ASSERT_EQ(d.runs(), 64u);
  ASSERT_EQ(d.width(), 14u);
  DesignProperties p = analyse(d);
  EXPECT_TRUE(p.proportional_frequencies);
  EXPECT_FALSE(p.strength_two);
  EXPECT_NEAR(p.max_abs_correlation, 0.0, 1e-12);
  for (const auto& levels : p.levels) {
    ASSERT_EQ(levels.values, (std::vector<double>{-1, 0, 1}));
    EXPECT_EQ(levels.counts, (std::vector<int>{32, 16, 16}));  // as in the published L64
  }
  request.doubled = "high";
  p = analyse(orthogonal_array(request));
  EXPECT_EQ(p.levels[0].counts, (std::vector<int>{16, 16, 32}));
}

TEST(OrthogonalArrayRequest, PicksStrictArraysWhenTheyExist) {
  struct Case { int runs; std::vector<std::pair<int, int>> levels; };
  for (const Case& c : std::vector<Case>{{9, {{3, 4}}}, {27, {{3, 13}}}, {8, {{2, 7}}}, {16, {{4, 5}}}, {25, {{5, 6}}},
                                         {18, {{2, 1}, {3, 7}}}, {18, {{3, 7}}}, {36, {{2, 11}, {3, 12}}},
                                         {36, {{3, 12}}}, {12, {{2, 11}}}, {64, {{4, 21}}}, {81, {{3, 40}}}}) {
    OaRequest request;
    request.runs = c.runs;
    request.levels = c.levels;
    Design d = orthogonal_array(request);
    EXPECT_EQ(static_cast<int>(d.runs()), c.runs);
    LevelMatrix indices(d.runs(), d.width());
    for (std::size_t j = 0; j < d.width(); ++j)
      for (std::size_t i = 0; i < d.runs(); ++i)
        indices(i, j) = static_cast<int>(std::lround((d.coded(i, j) + 1) / 2 * (d.levels[j] - 1)));
    EXPECT_TRUE(is_strength_two(indices)) << c.runs << " runs";
  }
}

TEST(OrthogonalArrayRequest, UnreachableRunsSayWhatWouldWork) {
  OaRequest request;
  request.runs = 10;
  request.levels = {{3, 3}};
  try {
    orthogonal_array(request);
    FAIL();
  } catch (const demcal::Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("no orthogonal array with 10 runs"), std::string::npos) << message;
    EXPECT_NE(message.find("9 (up to 4 columns)"), std::string::npos) << message;
  }
  request.runs = 9;
  request.levels = {{3, 5}};  // L9 has only 4 columns
  EXPECT_THROW(orthogonal_array(request), demcal::Error);
  EXPECT_THROW(parse_levels("3^x", 2), demcal::Error);
  EXPECT_THROW(parse_levels("1", 2), demcal::Error);
  EXPECT_EQ(parse_levels("2^1,3^7", 0), (std::vector<std::pair<int, int>>{{2, 1}, {3, 7}}));
}
