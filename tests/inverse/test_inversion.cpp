// The inverse problem on models with known answers: objectives by hand, a
// reachable target found to 1e-10 with the polish, an unreachable one flagged,
// parameters the targets cannot identify, fixed/tied/free parameters of a
// space, and the candidate set of the tolerance search.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/inverse/inversion.hpp"

namespace {

using namespace demcal;
using namespace demcal::inverse;

// strength = 2 a + b (a and b trade off: one equation, two unknowns);
// stiffness = 10 c + a / 10.
class Toy : public BoxModel {
 public:
  Toy() : BoxModel({{"a", 0, 6}, {"b", 0, 10}, {"c", 1, 3}}, {"strength", "stiffness"}) {}
  void predict(const double* x, double* y) const override {
    y[0] = 2.0 * x[0] + x[1];
    y[1] = 10.0 * x[2] + 0.1 * x[0];
  }
};

TEST(Objectives, HandComputed) {
  std::vector<double> y{11, 18, 0.25}, t{10, 20, 0.2};
  // relative errors 0.1, -0.1, 0.25
  EXPECT_NEAR(relative_objective(ObjectiveKind::SumRel, y, t), 0.45, 1e-15);
  EXPECT_NEAR(relative_objective(ObjectiveKind::MaxRel, y, t), 0.25, 1e-15);
  EXPECT_NEAR(relative_objective(ObjectiveKind::SseRel, y, t), 0.01 + 0.01 + 0.0625, 1e-15);
  EXPECT_NEAR(relative_objective(ObjectiveKind::SumRel, {-3}, {-2}), 0.5, 1e-15);  // |t| in the denominator
  // No prediction (a failed DEM run) is never a solution, whatever the objective.
  for (ObjectiveKind kind : {ObjectiveKind::SumRel, ObjectiveKind::MaxRel, ObjectiveKind::SseRel})
    EXPECT_EQ(relative_objective(kind, {std::nan(""), 18}, {10, 20}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_objective("max-rel"), ObjectiveKind::MaxRel);
  EXPECT_THROW(parse_objective("rms"), Error);
  // minimise: each output over its reference, summed (no target to meet).
  EXPECT_NEAR(relative_objective(ObjectiveKind::Minimise, {3.0, 1.0}, {6.0, -4.0}), 0.75, 1e-15);
  EXPECT_EQ(parse_objective("minimise"), ObjectiveKind::Minimise);
}

TEST(Inversion, MinimiseDrivesAnOutputDownAndIsNeverNotMet) {
  // strength = 2 a + b is least at a = b = 0 (the box's corner); over a reference of 10 the objective is 0 there.
  Toy toy;
  InversionProblem problem({&toy}, nullptr, {{"strength", 10.0}}, ObjectiveKind::Minimise);
  InversionSettings settings;
  settings.algorithm = "ga";
  settings.seed = 4;
  settings.budget.max_evaluations = 4000;
  settings.attainable_samples = 0;
  const InversionResult r = invert(problem, settings);
  EXPECT_EQ(r.status, "ok");
  EXPECT_LT(r.objective, 0.02);
  EXPECT_NEAR(r.predicted[0], 10.0 * r.objective, 1e-9);
  settings.algorithm = "search";
  EXPECT_THROW(invert(problem, settings), Error);
}

TEST(Inversion, ReachesATargetAndSaysWhatItCannotIdentify) {
  Toy toy;
  InversionProblem problem({&toy}, nullptr, {{"strength", 12.0}, {"stiffness", 20.5}}, ObjectiveKind::SumRel);
  InversionSettings settings;
  settings.restarts = 8;
  settings.polish = true;
  InversionResult r = invert(problem, settings);
  EXPECT_EQ(r.status, "ok");
  EXPECT_LT(r.objective, 1e-10);
  for (const RestartRecord& restart : r.restarts) EXPECT_TRUE(problem.bounds().contains(restart.x));
  // 2a + b = 12 has a line of solutions (a in [1, 6], b = 12 - 2a): both spread over most of
  // their ranges; c = (20.5 - a / 10) / 10 stays within [1.99, 2.04].
  ASSERT_EQ(r.spread.size(), 3u);
  EXPECT_FALSE(r.spread[0].identified) << r.spread[0].fraction;
  EXPECT_FALSE(r.spread[1].identified) << r.spread[1].fraction;
  EXPECT_TRUE(r.spread[2].identified) << r.spread[2].fraction;
  EXPECT_LT(r.spread[2].fraction, 0.3);
}

TEST(Inversion, UnreachableTargetIsFlaggedWithTheAttainableRange) {
  Toy toy;
  InversionProblem problem({&toy}, nullptr, {{"strength", 45.0}}, ObjectiveKind::SumRel);  // max 2*6 + 10 = 22
  InversionSettings settings;
  InversionResult r = invert(problem, settings);
  EXPECT_EQ(r.status, "unreachable");
  ASSERT_EQ(r.attainable.size(), 1u);
  EXPECT_FALSE(r.attainable[0].inside);
  EXPECT_NEAR(r.attainable[0].max, 22.0, 1e-6);  // the optimiser's best extends the sampled range
  nlohmann::json j = solution_json(problem, settings, r);
  EXPECT_EQ(j["status"], "unreachable");
  EXPECT_NE(j["reason"].get<std::string>().find("outside the attainable"), std::string::npos);
  EXPECT_NEAR(j["nearest_attainable"]["strength"].get<double>(), 22.0, 1e-6);
}

TEST(Inversion, AMissedButAttainableTargetIsNotMetNotUnreachable) {
  Toy toy;
  InversionProblem problem({&toy}, nullptr, {{"strength", 12.0}, {"stiffness", 20.5}}, ObjectiveKind::SumRel);
  InversionSettings settings;
  settings.budget.max_evaluations = 1;  // one random point: surely a miss
  InversionResult r = invert(problem, settings);
  EXPECT_EQ(r.status, "not_met");
  nlohmann::json j = solution_json(problem, settings, r);
  EXPECT_NE(j["reason"].get<std::string>().find("inside its attainable range"), std::string::npos);
  EXPECT_TRUE(j.contains("spread_note"));
}

TEST(Inversion, AModelThatPredictsNoTargetIsLeftOut) {
  Toy toy;
  class Other : public BoxModel {
   public:
    Other() : BoxModel({{"d", 0, 1}}, {"density"}) {}
    void predict(const double* x, double* y) const override { y[0] = x[0]; }
  } other;
  InversionProblem problem({&toy, &other}, nullptr, {{"strength", 12.0}}, ObjectiveKind::SumRel);
  EXPECT_EQ(problem.parameter_names(), (std::vector<std::string>{"a", "b", "c"}));  // no "d"
  ASSERT_EQ(problem.warnings().size(), 1u);
  EXPECT_NE(problem.warnings()[0].find("density"), std::string::npos);
}

TEST(Inversion, SpaceFixesTiesAndReportsFreeParameters) {
  Toy toy;
  nlohmann::json space_json = {
      {"parameters", {{{"name", "a"}, {"low", 1}, {"high", 5}}, {{"name", "b"}, {"low", 0}, {"high", 10}},
                      {{"name", "unused"}, {"low", 0}, {"high", 1}}}},
      {"fixed", {{"c", 2.0}}}};
  ParameterSpace space = ParameterSpace::from_json(space_json, "space.json");
  InversionProblem problem({&toy}, &space, {{"strength", 12.0}}, ObjectiveKind::MaxRel);
  EXPECT_EQ(problem.parameter_names(), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(problem.bounds().low, (Point{1, 0}));
  ASSERT_EQ(problem.free_parameters().size(), 1u);
  EXPECT_EQ(problem.free_parameters()[0].name, "unused");
  EXPECT_NEAR(problem.predict_all({3, 4})["stiffness"], 20.3, 1e-12);  // c fixed at 2

  nlohmann::json tied_json = {{"parameters", {{{"name", "a"}, {"low", 1}, {"high", 5}}, {{"name", "c"}, {"low", 1}, {"high", 3}}}},
                              {"tied", {{{"name", "b"}, {"source", "a"}, {"factor", 2.0}}}}};
  ParameterSpace tied = ParameterSpace::from_json(tied_json, "tied.json");
  InversionProblem tied_problem({&toy}, &tied, {{"strength", 12.0}}, ObjectiveKind::SumRel);
  EXPECT_NEAR(tied_problem.predict_targets({3, 2})[0], 2 * 3 + 6, 1e-12);  // b = 2a
}

TEST(Inversion, ClearErrors) {
  Toy toy;
  EXPECT_THROW(InversionProblem({&toy}, nullptr, {{"density", 1.0}}, ObjectiveKind::SumRel), Error);
  EXPECT_THROW(InversionProblem({&toy}, nullptr, {{"strength", 0.0}}, ObjectiveKind::SumRel), Error);
  EXPECT_THROW(InversionProblem({&toy, &toy}, nullptr, {{"strength", 1.0}}, ObjectiveKind::SumRel), Error);
  nlohmann::json missing = {{"parameters", {{{"name", "a"}, {"low", 1}, {"high", 5}}}}};
  ParameterSpace space = ParameterSpace::from_json(missing, "s.json");
  try {
    InversionProblem({&toy}, &space, {{"strength", 1.0}}, ObjectiveKind::SumRel);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("model input b is neither varied, fixed nor tied"), std::string::npos) << e.what();
  }
}

TEST(Inversion, ToleranceSearchReturnsClusterCentresAsCandidates) {
  Toy toy;
  InversionProblem problem({&toy}, nullptr, {{"strength", 12.0}, {"stiffness", 20.5}}, ObjectiveKind::SumRel);
  InversionSettings settings;
  settings.algorithm = "search";
  settings.search.samples = 4000;
  InversionResult r = invert(problem, settings);
  EXPECT_EQ(r.status, "ok");
  ASSERT_FALSE(r.candidates.empty());
  int total = 0;
  for (const Candidate& c : r.candidates) {
    total += c.size;
    EXPECT_TRUE(problem.bounds().contains(c.x));
  }
  EXPECT_EQ(total, r.spread_points);
  for (const Candidate& c : r.candidates)
    EXPECT_EQ(c.within_tolerance, c.max_relative_error <= settings.search.tolerance);
  EXPECT_EQ(r.spread_basis, "search points within the tolerance");
  EXPECT_LE(r.max_relative_error, settings.search.tolerance);
}

}  // namespace
