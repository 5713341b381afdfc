// The DEM as a model (DEM in the loop): a prediction is the DEM run itself,
// batches run in parallel and equal one-by-one runs, points asked for again
// are not rerun, and a second model on the same folder resumes from the
// stored runs instead of repeating them.
#include <gtest/gtest.h>

#include "../common/scratch.hpp"

#include <unistd.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/jobs/dem_model.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene_set.hpp"

using namespace demcal;
using namespace demcal::dem;
using namespace demcal::jobs;

namespace {

const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";

ParameterSpace space(const std::string& extra_fixed = "") {
  return ParameterSpace::from_json(nlohmann::json::parse(R"({"parameters": [
      {"name": "pb_sigma_c_MPa", "low": 8, "high": 16},
      {"name": "Ec_GPa", "low": 10, "high": 30}], "fixed": {"kn_ks": 1.5)" + extra_fixed + "}}"),
                                   "test space");
}

DemModelOptions options(const std::string& name, int jobs = 2) {
  DemModelOptions o;
  o.work_dir = demcal::test::scratch_path("dem_model_" + name);
  o.jobs = jobs;
  o.cache_dir = demcal::test::scratch_path("dem_model_cache");
  o.progress = false;
  return o;
}

}  // namespace

TEST(DemModel, APredictionIsTheDemRunAtThoseParameters) {
  DemModel model(kScene, space(), {"sigma_u_MPa", "E_GPa"}, options("direct"));
  EXPECT_EQ(model.inputs(), (std::vector<std::string>{"pb_sigma_c_MPa", "Ec_GPa"}));
  std::vector<double> y = model.predict(std::vector<double>{12.0, 20.0});

  Scene scene = Scene::load(kScene);
  RunOptions run;
  run.seed = 1;
  TestResult direct = run_test(scene, scene.resolve({{"pb_sigma_c_MPa", 12.0}, {"Ec_GPa", 20.0}, {"kn_ks", 1.5}}), run);
  ASSERT_TRUE(direct.ok) << direct.reason;
  EXPECT_DOUBLE_EQ(y[0], direct.macro.at("sigma_u_MPa"));
  EXPECT_DOUBLE_EQ(y[1], direct.macro.at("E_GPa"));
  EXPECT_EQ(model.runs_made(), 1);
}

TEST(DemModel, ABatchInParallelEqualsOneByOneAndRepeatsAreNotRerun) {
  const std::vector<std::vector<double>> xs = {{9.0, 12.0}, {12.0, 20.0}, {15.0, 28.0}};
  DemModel parallel(kScene, space(), {"sigma_u_MPa", "nu"}, options("parallel", 2));
  std::vector<std::vector<double>> batch;
  parallel.predict_batch(xs, batch);
  DemModel serial(kScene, space(), {"sigma_u_MPa", "nu"}, options("serial", 1));
  for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_EQ(serial.predict(xs[i]), batch[i]);
  EXPECT_LT(batch[0][0], batch[2][0]);  // stronger bonds, stronger specimen

  parallel.predict_batch({xs[1], xs[0]}, batch);
  EXPECT_EQ(parallel.points(), 3);
  EXPECT_EQ(parallel.runs_made(), 3);
}

TEST(DemModel, ANewModelOnTheSameFolderResumesWithoutRerunning) {
  const std::vector<std::vector<double>> xs = {{10.0, 15.0}, {14.0, 25.0}};
  std::vector<std::vector<double>> first, second;
  {
    DemModel model(kScene, space(), {"sigma_u_MPa"}, options("resume"));
    model.predict_batch(xs, first);
    EXPECT_EQ(model.runs_made(), 2);
  }
  DemModel again(kScene, space(), {"sigma_u_MPa"}, options("resume"));
  again.predict_batch(xs, second);
  EXPECT_EQ(second, first);
  EXPECT_EQ(again.runs_made(), 0);
  EXPECT_EQ(again.runs_reused(), 2);

  // The same run numbers with other values are run again, never reused.
  DemModel changed(kScene, space(), {"sigma_u_MPa"}, options("resume"));
  changed.predict_batch({{11.0, 15.0}}, second);
  EXPECT_EQ(changed.runs_made(), 1);
  EXPECT_NE(second[0][0], first[0][0]);

  std::ifstream csv(changed.evaluations_csv());
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "run,pb_sigma_c_MPa,Ec_GPa,sigma_u_MPa,seeds,status");
}

TEST(DemModel, AFailedRunGivesNoNumberAndBadSetupsAreErrors) {
  // A space reaching beyond the scene's own bounds [0.1, 500] is refused.
  ParameterSpace wide = ParameterSpace::from_json(
      nlohmann::json::parse(R"({"parameters": [{"name": "Ec_GPa", "low": 10, "high": 700}]})"), "wide");
  try {
    DemModel(kScene, wide, {"sigma_u_MPa"}, options("wide"));
    FAIL() << "a space wider than the scene's bounds was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("high 700 lies outside the bounds [0.1, 500]"), std::string::npos) << e.what();
  }
  // A point asked for beyond them (Ec_GPa = 600) is a failed run, not a number.
  ParameterSpace inside = ParameterSpace::from_json(
      nlohmann::json::parse(R"({"parameters": [{"name": "Ec_GPa", "low": 10, "high": 500}]})"), "inside");
  DemModel model(kScene, inside, {"sigma_u_MPa"}, options("failed"));
  EXPECT_TRUE(std::isnan(model.predict(std::vector<double>{600.0})[0]));
  EXPECT_EQ(model.runs_failed(), 1);

  try {
    DemModel(kScene, space(R"(, "porosity_target": 0.1)"), {"sigma_u_MPa"}, options("bad"));
    FAIL() << "a space parameter the scene does not have was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("\"porosity_target\" is not a parameter of the scene"), std::string::npos) << e.what();
  }
  try {
    DemModel unknown_output(kScene, space(), {"UCS"}, options("unknown"));
    FAIL() << "an output the DEM does not give was accepted";
  } catch (const Error& e) {  // found before any run
    EXPECT_NE(std::string(e.what()).find("the DEM gives no output \"UCS\" (it gives "), std::string::npos) << e.what();
  }
}

TEST(DemModel, ARatioOutputIsFormedPerSpecimenOverATestList) {
  // sigma_t / sigma_u of one material from a UCS and a Brazilian test per point,
  // each seed's own ratio averaged (not the ratio of the means).
  const std::string list = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/tests_small.json";
  DemModelOptions o = options("ratio");
  o.seeds = 2;
  DemModel model(list, space(), {"sigma_t_MPa/sigma_u_MPa", "sigma_u_MPa"}, o);
  std::vector<double> y = model.predict(std::vector<double>{12.0, 20.0});
  const SceneSet set = SceneSet::load(list);
  double mean_ratio = 0, mean_ucs = 0;
  for (std::uint64_t seed : {1, 2}) {
    RunOptions run;
    run.seed = seed;
    const nlohmann::json r = set.run(set.resolve({{"pb_sigma_c_MPa", 12.0}, {"Ec_GPa", 20.0}, {"kn_ks", 1.5}}), run);
    ASSERT_EQ(r.at("status"), "ok") << r.at("reason");
    const double t = r.at("macro").at("sigma_t_MPa").get<double>(), u = r.at("macro").at("sigma_u_MPa").get<double>();
    mean_ratio += t / u / 2;
    mean_ucs += u / 2;
  }
  EXPECT_DOUBLE_EQ(y[0], mean_ratio);
  EXPECT_DOUBLE_EQ(y[1], mean_ucs);
  EXPECT_EQ(model.runs_made(), 2);  // points x seeds; each ran all three tests
  // A ratio of something the tests do not give is an error naming it, before any run.
  try {
    DemModel bad(list, space(), {"sigma_t_MPa/nothing"}, options("ratio_bad"));
    ADD_FAILURE() << "no error";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("gives no output \"nothing\" (in the ratio sigma_t_MPa/nothing)"),
              std::string::npos) << e.what();
  }
}
