// demcal-analyze, demcal-fit and demcal-predict as users and the pipeline call
// them: the interface's JSON shapes, the prediction file, domain warnings and
// one-line errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../common/command.hpp"
#include "demcal/core/table.hpp"
#include "fixtures.hpp"

namespace {

using demcal::test::expect_one_line_error;
using demcal::test::literature;
using demcal::test::run_program;
using demcal::test::temp_path;

const std::string kL64Factors =
    "Ec_GPa,kn_ks,pb_sigma_c_MPa,pb_tau_c_MPa,mu,Ec_g_GPa,kn_ks_g,mu_g,Ec_j_GPa,kn_ks_j,pb_sigma_c_j_MPa,"
    "pb_tau_c_j_MPa,mu_j,null_column";

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(demcal::test::slurp(path)); }

TEST(DemcalAnalyze, AnovaJsonHasTheInterfaceShape) {
  std::string out = temp_path("anova.json");
  auto r = run_program("demcal-analyze", "anova --data " + literature("su2021_L64_orthogonal.csv") + " --factors " +
                                             kL64Factors + " --responses sigma_u_MPa,E_GPa,nu --format json --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = read_json(out);
  ASSERT_TRUE(j.contains("E_GPa"));
  EXPECT_EQ(j["E_GPa"].size(), 15u);  // 14 terms + error
  for (const char* key : {"ss", "df", "ms", "F", "p"}) EXPECT_TRUE(j["E_GPa"]["Ec_GPa"].contains(key)) << key;
  EXPECT_EQ(j["E_GPa"]["error"]["df"], 35);
  EXPECT_NEAR(j["E_GPa"]["Ec_GPa"]["F"].get<double>(), 3004.5886020775552, 1e-7);
  EXPECT_EQ(j["sigma_u_MPa"]["pb_sigma_c_MPa"]["significance"], "**");
}

TEST(DemcalAnalyze, TextbookErrorColumnAndMarkdown) {
  auto r = run_program("demcal-analyze", "anova --data " + literature("su2021_L64_orthogonal.csv") + " --factors " +
                                             kL64Factors + " --responses sigma_u_MPa --error column:null_column");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("| pb_sigma_c_MPa | 2 | 3162.97 | 1581.49 | 414.473 | 0.0024 | ** highly significant |"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("| Error | 2 | 7.63132 |"), std::string::npos) << r.out;
  // The model's residual is then in no test; it is shown so the table adds up to the total.
  EXPECT_NE(r.out.find("| Residual (not in the error) | 35 | 1306.16 |"), std::string::npos) << r.out;
}

TEST(DemcalAnalyze, RangeJson) {
  std::string out = temp_path("range.json");
  auto r = run_program("demcal-analyze", "range --data " + literature("su2021_L64_orthogonal.csv") + " --factors " +
                                             kL64Factors + " --responses E_GPa --format json --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = read_json(out)["E_GPa"]["factors"];
  EXPECT_EQ(j["Ec_GPa"]["rank"], 1);
  EXPECT_EQ(j["Ec_GPa"]["count"], nlohmann::json({32, 16, 16}));
}

TEST(DemcalAnalyze, Errors) {
  std::string data = " --data " + literature("su2021_L64_orthogonal.csv");
  expect_one_line_error(run_program("demcal-analyze", "anova" + data + " --factors Ec_GPa,nope --responses nu"),
                        "demcal-analyze", "no column \"nope\"");
  expect_one_line_error(run_program("demcal-analyze", "anova --data /nonexistent.csv --factors a --responses b"),
                        "demcal-analyze", "/nonexistent.csv");
  expect_one_line_error(run_program("demcal-analyze", "anova" + data + " --factors Ec_GPa --responses nu --error blank"),
                        "demcal-analyze", "expected residual or column:NAME");
  expect_one_line_error(run_program("demcal-analyze", "anova" + data + " --factors Ec_GPa,kn_ks --responses Ec_GPa"),
                        "demcal-analyze", "both a factor (--factors) and a response");
}

TEST(DemcalFit, QuadraticModelFileAndPredict) {
  std::string model = temp_path("ccd.json"), residuals = temp_path("ccd_res.csv");
  auto r = run_program("demcal-fit", "quadratic --data " + literature("su2021_CCD2_sigma_u.csv") +
                                         " --x pb_sigma_c_MPa,pb_tau_c_MPa --y sigma_u_MPa --out " + model +
                                         " --residuals " + residuals + " --seed 3");  // --seed: accepted, no effect
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("Lack-of-Fit | 3 |"), std::string::npos) << r.out;
  nlohmann::json j = read_json(model);
  for (const char* term : {"1", "pb_sigma_c_MPa", "pb_tau_c_MPa", "pb_sigma_c_MPa^2", "pb_tau_c_MPa^2",
                           "pb_sigma_c_MPa*pb_tau_c_MPa"})
    EXPECT_TRUE(j["coefficients"].contains(term)) << term;
  EXPECT_EQ(j["coefficients"].size(), 6u);
  EXPECT_NEAR(j["r2"].get<double>(), 0.98813142478526328, 1e-12);
  EXPECT_NEAR(j["r2_adj"].get<double>(), 0.97965387106045143, 1e-12);
  EXPECT_NEAR(j["r2_pred"].get<double>(), 0.93869881177548753, 1e-10);
  std::string res = demcal::test::slurp(residuals);
  EXPECT_EQ(std::count(res.begin(), res.end(), '\n'), 14);  // header + 13 runs
  EXPECT_EQ(res.rfind("run,response,observed,fitted,residual,press_residual\n", 0), 0u);

  std::string rows = temp_path("new_rows.csv"), predictions = temp_path("predictions.csv");
  {
    std::ofstream(rows) << "run,pb_sigma_c_MPa,pb_tau_c_MPa\n1,20,20\n2,40,20\n3,10,0\n";
  }
  auto p = run_program("demcal-predict", "--model " + model + " --data " + rows + " --out " + predictions);
  ASSERT_EQ(p.code, 0) << p.err;
  demcal::Table t = demcal::Table::read_csv(predictions);
  EXPECT_EQ(t.names(), (std::vector<std::string>{"pb_sigma_c_MPa", "pb_tau_c_MPa", "sigma_u_MPa"}));
  EXPECT_NEAR(t.at(0, "sigma_u_MPa"), 41.339992883245884, 1e-9);  // the coded constant: the centre point
  EXPECT_EQ(t.run_ids(), (std::vector<int>{1, 2, 3}));
  // One warning per row outside the fitted domain (runs 2 and 3).
  EXPECT_NE(p.err.find("warning: run 2: outside the fitted domain (pb_sigma_c_MPa = 40"), std::string::npos) << p.err;
  EXPECT_NE(p.err.find("warning: run 3:"), std::string::npos) << p.err;
  EXPECT_EQ(p.err.find("warning: run 1:"), std::string::npos) << p.err;
}

TEST(DemcalFit, GabpOnThePublishedDatabase) {
  std::string model = temp_path("nn.json"), predictions = temp_path("nn_pred.csv");
  auto r = run_program("demcal-fit", "gabp --data " + literature("he2019_gabp_train.csv") +
                                         " --x e_pp,mu_pp,e_pw,mu_pw,surface_energy_as_printed --y aor_deg --out " +
                                         model + " --seed 3 --hidden 7 --validation-fraction 0.25 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = read_json(model);
  EXPECT_EQ(j["kind"], "gabp");
  EXPECT_EQ(j["network"]["hidden"], 7);
  EXPECT_EQ(j["validation"]["rows"], 20);
  EXPECT_GT(j["validation"]["r2"]["aor_deg"].get<double>(), 0.9);
  auto p = run_program("demcal-predict", "--model " + model + " --data " + literature("he2019_funnel_tests.csv") +
                                             " --out " + predictions);
  // The funnel tests hold only measured angles: predict names the missing input.
  expect_one_line_error(p, "demcal-predict", "no column \"e_pp\"");
  auto q = run_program("demcal-predict", "--model " + model + " --data " + literature("he2019_gabp_train.csv") +
                                             " --out " + predictions);
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_EQ(demcal::Table::read_csv(predictions).rows(), 80u);
}

TEST(DemcalFit, Errors) {
  std::string bbd = " --data " + literature("su2021_BBD4_nu.csv");
  expect_one_line_error(run_program("demcal-fit", "quadratic" + bbd + " --x Ec_GPa,kn_ks,mu,missing --y nu --out /tmp/x.json"),
                        "demcal-fit", "no column \"missing\"");
  // A 3-factor quadratic has 10 terms; 7 runs cannot carry it.
  std::string small = temp_path("small.csv");
  {
    std::ofstream(small) << "A,B,C,y\n1,1,1,1\n2,1,2,3\n3,2,1,2\n1,3,3,5\n2,2,2,4\n3,3,1,2\n1,2,3,6\n";
  }
  expect_one_line_error(run_program("demcal-fit", "quadratic --data " + small + " --x A,B,C --y y --out /tmp/x.json"),
                        "demcal-fit", "needs at least 11 runs");
  std::string constant = temp_path("constant.csv");
  {
    std::ofstream(constant) << "A,B,y\n1,5,1\n2,5,3\n3,5,2\n1,5,5\n";
  }
  expect_one_line_error(run_program("demcal-fit", "linear --data " + constant + " --x A,B --y y --out /tmp/x.json"),
                        "demcal-fit", "column B is constant");
  expect_one_line_error(run_program("demcal-fit", "quadratic" + bbd + " --x Ec_GPa --y nu --hidden 3 --out /tmp/x.json"),
                        "demcal-fit", "--hidden does not apply to quadratic");
  expect_one_line_error(run_program("demcal-predict", "--model /nonexistent.json --data x.csv --out y.csv"),
                        "demcal-predict", "/nonexistent.json: cannot open model");
}

TEST(DemcalAnalyze, SobolOnASavedModel) {
  std::string model = temp_path("nu.json"), out = temp_path("sobol.json");
  ASSERT_EQ(run_program("demcal-fit", "quadratic --data " + literature("su2021_BBD4_nu.csv") +
                                          " --x Ec_GPa,kn_ks,mu,kn_ks_j --y nu --quiet --out " + model).code, 0);
  auto r = run_program("demcal-analyze", "sobol --model " + model + " --samples 1024 --format json --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json j = read_json(out)["nu"]["inputs"];
  // kn/ks drives nu (the published conclusion and the range analysis agree).
  EXPECT_GT(j["kn_ks"]["ST"].get<double>(), 0.8);
}

}  // namespace
