// demcal-invert as users call it, on response surfaces fitted to the published
// runs of Su et al. (2021): a C30-like target met to sum-rel < 1e-4, the
// SOLUTION.json shape, exit code 3 for an unreachable target, one-line errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../common/command.hpp"

namespace {

using demcal::test::expect_one_line_error;
using demcal::test::run_program;
using demcal::test::temp_path;

std::string literature(const std::string& file) { return std::string(DEMCAL_SOURCE_DIR) + "/data/literature/" + file; }

// The three published surfaces, fitted once for the suite.
class DemcalInvert : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    models_ = " --model " + fit("sigma_u", "su2021_CCD2_sigma_u.csv", "pb_sigma_c_MPa,pb_tau_c_MPa", "sigma_u_MPa") +
              " --model " + fit("E", "su2021_BBD5_E.csv", "Ec_GPa,kn_ks,mu,Ec_j_GPa,kn_ks_j", "E_GPa") +
              " --model " + fit("nu", "su2021_BBD4_nu.csv", "Ec_GPa,kn_ks,mu,kn_ks_j", "nu");
  }
  static std::string fit(const std::string& name, const std::string& data, const std::string& x, const std::string& y) {
    std::string out = temp_path("invert_" + name + ".json");
    auto r = run_program("demcal-fit", "quadratic --quiet --data " + literature(data) + " --x " + x + " --y " + y + " --out " + out);
    EXPECT_EQ(r.code, 0) << r.err;
    return out;
  }
  static std::string models_;
};
std::string DemcalInvert::models_;

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(demcal::test::slurp(path)); }

TEST_F(DemcalInvert, MeetsNewTargetsInsideTheFittedRanges) {
  std::string out = temp_path("solution.json"), history = temp_path("history.csv");
  auto r = run_program("demcal-invert", models_ + " --target sigma_u_MPa=30 --target E_GPa=30 --target nu=0.2" +
                                            " --algo ga --objective sum-rel --seed 3 --restarts 4 --out " + out +
                                            " --history " + history);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json s = read_json(out);
  EXPECT_EQ(s["status"], "ok");
  EXPECT_LT(s["objective"].get<double>(), 1e-4);
  EXPECT_LT(s["wall_s"].get<double>(), 2.0);  // measured 0.05 s on the 2-core CI machine
  for (const char* key : {"x", "predicted", "objective", "evaluations", "restarts", "candidates"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["x"].size(), 7u);
  EXPECT_NEAR(s["predicted"]["E_GPa"].get<double>(), 30.0, 30.0 * 1e-4);
  EXPECT_EQ(s["restarts"].size(), 4u);
  // Strength depends on two bond strengths only: the restarts spread along that trade-off.
  bool names_strength = false;
  for (const auto& u : s["unidentified"]) names_strength = names_strength || u == "pb_tau_c_MPa" || u == "pb_sigma_c_MPa";
  EXPECT_TRUE(names_strength) << s["unidentified"];
  EXPECT_EQ(demcal::test::slurp(history).rfind("algorithm,restart,seed,evaluations,best_objective\n", 0), 0u);
}

TEST_F(DemcalInvert, EveryAlgorithmWithPolishMeetsTheTargets) {
  for (const char* algo : {"ga", "sa", "wca", "lhs-wca", "search"}) {
    std::string out = temp_path(std::string("solution_") + algo + ".json");
    auto r = run_program("demcal-invert", models_ + " --target sigma_u_MPa=40 --target E_GPa=25 --target nu=0.22 --algo " +
                                              algo + " --polish --out " + out);
    ASSERT_EQ(r.code, 0) << algo << ": " << r.err;
    EXPECT_LT(read_json(out)["max_relative_error"].get<double>(), 1e-6) << algo;
  }
}

TEST_F(DemcalInvert, UnreachableTargetExitsWithCodeThree) {
  std::string out = temp_path("unreachable.json");
  auto r = run_program("demcal-invert", models_ + " --target sigma_u_MPa=150 --target E_GPa=30 --out " + out);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("sigma_u_MPa = 150 lies outside the attainable"), std::string::npos) << r.err;
  nlohmann::json s = read_json(out);
  EXPECT_EQ(s["status"], "unreachable");
  EXPECT_FALSE(s["attainable"]["sigma_u_MPa"]["inside"].get<bool>());
  EXPECT_TRUE(s.contains("nearest_attainable"));
}

TEST_F(DemcalInvert, AnOptimiserThatMissesAttainableTargetsExitsWithCodeFour) {
  std::string out = temp_path("not_met.json");
  auto r = run_program("demcal-invert", models_ + " --target sigma_u_MPa=30 --target E_GPa=30 --target nu=0.2 --budget 1 --out " + out);
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(read_json(out)["status"], "not_met");
  EXPECT_NE(r.err.find("targets not met"), std::string::npos) << r.err;
}

TEST_F(DemcalInvert, Errors) {
  expect_one_line_error(run_program("demcal-invert", models_ + " --target density=2400 --out /tmp/x.json"), "demcal-invert",
                        "no model predicts it");
  expect_one_line_error(run_program("demcal-invert", models_ + " --target E_GPa --out /tmp/x.json"), "demcal-invert",
                        "expected NAME=VALUE");
  const std::string all = " --target E_GPa=30 --target sigma_u_MPa=30 --target nu=0.2";
  expect_one_line_error(run_program("demcal-invert", models_ + all + " --set populaton=300 --out /tmp/x.json"),
                        "demcal-invert", "setting \"populaton\" does not apply to ga");
  expect_one_line_error(run_program("demcal-invert", models_ + all + " --algo pso --out /tmp/x.json"),
                        "demcal-invert", "unknown algorithm \"pso\"");
  expect_one_line_error(run_program("demcal-invert", models_ + all + " --objective minimise --polish --out /tmp/x.json"),
                        "demcal-invert", "--objective minimise has none to fit");
  expect_one_line_error(run_program("demcal-invert", " --model /nonexistent.json --target E_GPa=30 --out /tmp/x.json"),
                        "demcal-invert", "/nonexistent.json: cannot open model");
}

}  // namespace

namespace {

TEST(DemcalVerify, RunsTheSolutionOverSeedsAndWritesTheTable) {
  std::string solution = temp_path("verify_solution.json"), out = temp_path("verify.json"), md = temp_path("verify.md");
  {
    std::ofstream(solution) << R"({"status": "ok", "x": {"pb_sigma_c_MPa": 12, "pb_tau_c_MPa": 30},
                                   "targets": {"sigma_u_MPa": 15, "E_GPa": 20}, "predicted": {"sigma_u_MPa": 15}})";
  }
  std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  auto r = run_program("demcal-verify", "--solution " + solution + " --scene " + scene + " --seeds 2 --max-seeds 2 --jobs 2 --out " + out +
                                            " --md " + md + " --cache " + temp_path("verify_cache") + " --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json v = read_json(out);
  ASSERT_EQ(v["seeds"].size(), 2u);
  EXPECT_EQ(v["seeds"][0]["status"], "ok");
  EXPECT_EQ(v["outputs"]["sigma_u_MPa"]["runs"], 2);
  EXPECT_GT(v["outputs"]["sigma_u_MPa"]["mean"].get<double>(), 1.0);
  EXPECT_EQ(v["parameters"]["pb_sigma_c_MPa"], 12.0);
  EXPECT_NE(demcal::test::slurp(md).find("| E_GPa | 20 |"), std::string::npos);

  // Other specimens (after a calibration on seed 1, say): seeds 3 and 4, not 1 and 2.
  const std::string later = temp_path("verify_later.json");
  auto l = run_program("demcal-verify", "--solution " + solution + " --scene " + scene + " --seeds 2 --max-seeds 2 --first-seed 3 --jobs 2 " +
                                            "--out " + later + " --cache " + temp_path("verify_cache") + " --quiet");
  ASSERT_EQ(l.code, 0) << l.err;
  nlohmann::json w = read_json(later);
  ASSERT_EQ(w["seeds"].size(), 2u);
  EXPECT_EQ(w["seeds"][0]["seed"], 3);
  EXPECT_EQ(w["seeds"][1]["seed"], 4);
  EXPECT_NE(w["outputs"]["sigma_u_MPa"]["mean"], v["outputs"]["sigma_u_MPa"]["mean"]);

  EXPECT_EQ(w["seeds_stop_reason"], "--max-seeds reached");
  EXPECT_TRUE(w["outputs"]["sigma_u_MPa"]["ci95_low"].get<double>() < w["outputs"]["sigma_u_MPa"]["mean"].get<double>());

  std::string bad = temp_path("verify_bad.json");
  {
    std::ofstream(bad) << R"({"x": {"density": 1}, "targets": {"E_GPa": 20}})";
  }
  expect_one_line_error(run_program("demcal-verify", "--solution " + bad + " --scene " + scene + " --out " + out),
                        "demcal-verify", "unknown parameter \"density\"");
  expect_one_line_error(run_program("demcal-verify", "--solution " + solution + " --scene " + scene + " --seeds 5 " +
                                                         "--max-seeds 3 --out " + out),
                        "demcal-verify", "--max-seeds (3) must be at least --seeds (5)");
}

TEST(DemcalVerify, AMinimisationIsJudgedAgainstWhatItsOptimiserSawAndReportedAgainstItsReference) {
  // "targets" of a minimisation are references (the outputs were divided by them), "predicted" what the
  // optimiser saw at its answer: the verification judges the second and reports the mean over the first.
  const std::string solution = temp_path("verify_minimise.json"), out = temp_path("verify_minimise_out.json"),
                    md = temp_path("verify_minimise.md");
  {
    std::ofstream(solution) << R"({"status": "ok", "objective_kind": "minimise", "x": {"pb_sigma_c_MPa": 12, "pb_tau_c_MPa": 30},
                                   "targets": {"E_GPa": 400}, "predicted": {"E_GPa": 1000}})";
  }
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  auto r = run_program("demcal-verify", "--solution " + solution + " --scene " + scene + " --seeds 2 --max-seeds 2 --jobs 2 --out " +
                                            out + " --md " + md + " --cache " + temp_path("verify_cache") + " --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json v = read_json(out);
  const double mean = v["outputs"]["E_GPa"]["mean"].get<double>();
  ASSERT_GT(mean, 1.0);
  EXPECT_EQ(v["outputs"]["E_GPa"]["target"], 1000.0);  // the optimiser's value, not the reference
  EXPECT_NEAR(v["outputs"]["E_GPa"]["relative_error_pct"].get<double>(), 100 * (mean - 1000) / 1000, 1e-9);
  EXPECT_FALSE(v["passed"].get<bool>());
  EXPECT_EQ(v["objective_kind"], "minimise");
  EXPECT_EQ(v["references"]["E_GPa"], 400.0);
  EXPECT_NEAR(v["mean_over_reference"]["E_GPa"].get<double>(), mean / 400, 1e-12);
  EXPECT_NE(demcal::test::slurp(md).find("| E_GPa | 400 |"), std::string::npos);

  const std::string unseen = temp_path("verify_minimise_unseen.json");
  {
    std::ofstream(unseen) << R"({"objective_kind": "minimise", "x": {"pb_sigma_c_MPa": 12}, "targets": {"E_GPa": 400}})";
  }
  expect_one_line_error(run_program("demcal-verify", "--solution " + unseen + " --scene " + scene + " --out " + out),
                        "demcal-verify", "predicted.E_GPa is missing");
}

TEST(DemcalVerify, ScaleResolutionVerifiesOnFinerSpecimensAndReportsTheShift) {
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  const std::string solution = temp_path("verify_fine_solution.json"), out = temp_path("verify_fine.json");
  const std::string md = temp_path("verify_fine.md");
  {
    std::ofstream(solution) << R"({"x": {"pb_sigma_c_MPa": 12, "pb_tau_c_MPa": 30}, "targets": {"sigma_u_MPa": 15},
                                   "prediction_interval_95": {"sigma_u_MPa": [13, 17]}})";
  }
  auto r = run_program("demcal-verify", "--solution " + solution + " --scene " + scene + " --seeds 2 --max-seeds 2 " +
                                            "--scale-resolution 1.5 --finer-seeds 2 --jobs 2 --out " + out + " --md " + md +
                                            " --cache " + temp_path("verify_cache") + " --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json v = read_json(out);
  ASSERT_TRUE(v.contains("finer"));
  EXPECT_EQ(v["finer"]["factor"], 1.5);
  EXPECT_EQ(v["finer"]["seeds"].size(), 2u);
  const double coarse = v["outputs"]["sigma_u_MPa"]["mean"].get<double>();
  const double fine = v["finer"]["outputs"]["sigma_u_MPa"]["mean"].get<double>();
  EXPECT_NEAR(v["finer"]["shift_pct"]["sigma_u_MPa"].get<double>(), 100.0 * (fine - coarse) / coarse, 1e-9);
  // Finer specimens have more disks: the runs' files say so.
  const nlohmann::json coarse_run = read_json(temp_path("verify_fine.json.runs") + "/runs.h5.points/run1_seed1.json");
  const nlohmann::json fine_run = read_json(temp_path("verify_fine.json.runs") + "/finer_runs.h5.points/run1_seed1.json");
  EXPECT_GT(fine_run["particles"].get<double>(), 1.8 * coarse_run["particles"].get<double>());
  const std::string table = demcal::test::slurp(md);
  EXPECT_NE(table.find("At a finer resolution (disk radii / 1.5, 2 seeds)"), std::string::npos) << table;
  EXPECT_NE(table.find("| 13 to 17 |"), std::string::npos) << table;  // the surrogate's interval beside the DEM's
  EXPECT_EQ(v["outputs"]["sigma_u_MPa"]["predicted_interval_95"], nlohmann::json({13, 17}));
  expect_one_line_error(run_program("demcal-verify", "--solution " + solution + " --scene " + scene +
                                                         " --scale-resolution 0.5 --out " + out),
                        "demcal-verify", "--scale-resolution must be above 1");
}

TEST(DemcalVerify, AddsSeedsUntilTheIntervalIsNarrowOrTheLimit) {
  // Two seeds first, to learn the mean; then a target at that mean with a
  // tolerance no spread can meet: the mean is inside the band, the interval is
  // not narrow enough, so seeds are added (seeds 1 and 2 reused) up to --max-seeds.
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  const std::string first = temp_path("verify_grow_first.json"), solution = temp_path("verify_grow_solution.json");
  const std::string work = temp_path("verify_grow_runs"), cache = temp_path("verify_cache");
  {
    std::ofstream(first) << R"({"x": {"pb_sigma_c_MPa": 12, "pb_tau_c_MPa": 30}, "targets": {"sigma_u_MPa": 15}})";
  }
  auto r = run_program("demcal-verify", "--solution " + first + " --scene " + scene + " --seeds 2 --max-seeds 2 --jobs 2 " +
                                            "--work " + work + " --out " + temp_path("verify_grow_a.json") + " --cache " + cache +
                                            " --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const double mean = read_json(temp_path("verify_grow_a.json"))["outputs"]["sigma_u_MPa"]["mean"].get<double>();
  {
    nlohmann::json s = {{"x", {{"pb_sigma_c_MPa", 12}, {"pb_tau_c_MPa", 30}}}, {"targets", {{"sigma_u_MPa", mean}}}};
    std::ofstream(solution) << s.dump();
  }
  const std::string out = temp_path("verify_grow_b.json");
  auto g = run_program("demcal-verify", "--solution " + solution + " --scene " + scene + " --seeds 2 --max-seeds 4 " +
                                            "--tolerance 1e-9 --jobs 2 --work " + work + " --out " + out + " --cache " + cache);
  ASSERT_EQ(g.code, 0) << g.err;
  nlohmann::json v = read_json(out);
  ASSERT_EQ(v["seeds"].size(), 4u);
  EXPECT_EQ(v["seeds"][3]["seed"], 4);
  EXPECT_EQ(v["seeds_stop_reason"], "--max-seeds reached");
  EXPECT_EQ(v["outputs"]["sigma_u_MPa"]["runs"], 4);
  EXPECT_EQ(v["outputs"]["sigma_u_MPa"]["verdict"], "outside");  // the 4-seed mean moved off a 1e-9 band
  EXPECT_NE(g.err.find("2 seeds give 95 % half-widths sigma_u_MPa"), std::string::npos) << g.err;
  EXPECT_NE(g.err.find("resuming: 2 of 4 points already done"), std::string::npos) << g.err;
}

}  // namespace

namespace {

// DEM in the loop (Wang & Cao 2017): the annealing drives the DEM itself.
class DemcalInvertDemInTheLoop : public ::testing::Test {
 protected:
  void SetUp() override {
    space_ = temp_path("dem_loop_space.json");
    std::ofstream(space_) << R"({"parameters": [
        {"name": "Ec_GPa", "low": 8, "high": 30},
        {"name": "pb_sigma_c_MPa", "low": 8, "high": 16},
        {"name": "pb_tau_c_MPa", "low": 20, "high": 40}]})";
  }
  std::string args(const std::string& out) const {
    return "--dem-scene " + scene_ + " --space " + space_ +
           " --target sigma_u_MPa=21 --target E_GPa=25 --algo sa --objective max-rel --set parallel_trials=2"
           " --jobs 2 --budget 300 --cache " + temp_path("dem_loop_cache") + " --out " + out;
  }
  std::string scene_ = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  std::string space_;
};

TEST_F(DemcalInvertDemInTheLoop, AnnealingMeetsTargetsOnTheDemAndARerunRepeatsNoRun) {
  const std::string out = temp_path("dem_loop.json");
  auto r = run_program("demcal-invert", args(out));
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json s = read_json(out);
  EXPECT_EQ(s["status"], "ok");
  EXPECT_LE(s["max_relative_error"].get<double>(), 0.10);  // Wang & Cao's stop
  const long runs = s["dem"]["runs"].get<long>();
  EXPECT_GE(runs, 1);
  EXPECT_LE(runs, s["evaluations"].get<long>());
  EXPECT_EQ(s["dem"]["runs_made_now"].get<long>(), runs);

  // The solution's predicted values are those of a DEM run at its parameters.
  std::string sets;
  for (auto it = s["x"].begin(); it != s["x"].end(); ++it)
    sets += " --set " + it.key() + "=" + nlohmann::json(it.value().get<double>()).dump();
  const std::string run_out = temp_path("dem_loop_check.json");
  auto check = run_program("demcal-dem", "run --scene " + scene_ + sets + " --seed 1 --quiet --cache " +
                                             temp_path("dem_loop_cache") + " --out " + run_out);
  ASSERT_EQ(check.code, 0) << check.err;
  nlohmann::json direct = read_json(run_out);
  EXPECT_DOUBLE_EQ(s["predicted"]["sigma_u_MPa"].get<double>(), direct["macro"]["sigma_u_MPa"].get<double>());
  EXPECT_DOUBLE_EQ(s["predicted"]["E_GPa"].get<double>(), direct["macro"]["E_GPa"].get<double>());

  // Rerun (as after a crash): the same points, every DEM run taken from the folder.
  auto again = run_program("demcal-invert", args(out));
  ASSERT_EQ(again.code, 0) << again.err;
  nlohmann::json t = read_json(out);
  EXPECT_EQ(t["x"], s["x"]);
  EXPECT_EQ(t["dem"]["runs_made_now"], 0);
  EXPECT_EQ(t["dem"]["runs_reused"].get<long>(), runs);
}

TEST_F(DemcalInvertDemInTheLoop, Errors) {
  const std::string out = temp_path("dem_loop_err.json");
  expect_one_line_error(run_program("demcal-invert", args(out) + " --model " + temp_path("m.json")), "demcal-invert",
                        "not both");
  expect_one_line_error(run_program("demcal-invert", "--dem-scene " + scene_ + " --target E_GPa=20 --out " + out),
                        "demcal-invert", "--dem-scene needs --space");
  expect_one_line_error(run_program("demcal-invert", args(out) + " --polish"), "demcal-invert", "--polish");
  expect_one_line_error(run_program("demcal-invert", "--model " + temp_path("m.json") + " --target E_GPa=20 --jobs 2 --out " + out),
                        "demcal-invert", "--jobs applies to --dem-scene only");
}

}  // namespace

TEST(DemcalInvertList, AlgorithmsAndObjectivesAreListedForTheStudyLayer) {
  auto r = run_program("demcal-invert", "--list-algorithms");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json listed = nlohmann::json::parse(r.out);
  EXPECT_EQ(listed["algorithms"], nlohmann::json({"ga", "sa", "sa-vfsr", "wca", "lhs-wca", "hs", "search"}));
  EXPECT_EQ(listed["objectives"], nlohmann::json({"sum-rel", "max-rel", "sse-rel", "minimise"}));
  auto missing = run_program("demcal-invert", "--out x.json");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("--target NAME=VALUE is required"), std::string::npos) << missing.err;
}
