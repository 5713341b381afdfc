// demcal-doe as users and scripts call it: exit codes, one-line errors, files.
#include <gtest/gtest.h>

#include "../common/scratch.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/table.hpp"

namespace {

struct Result {
  int code;
  std::string out;
  std::string err;
};

std::string temp(const std::string& name) {
  return demcal::test::scratch_path(name);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Result run(const std::string& arguments) {
  std::string out = temp("stdout"), err = temp("stderr");
  std::string command = std::string(DEMCAL_BIN_DIR) + "/demcal-doe " + arguments + " >" + out + " 2>" + err;
  int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

std::string data(const std::string& relative) { return std::string(DEMCAL_SOURCE_DIR) + "/data/" + relative; }

// A failed call prints exactly one line that starts with the program name.
void expect_one_line_error(const Result& r, const std::string& fragment) {
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("demcal-doe: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

}  // namespace

TEST(DemcalDoe, The64RunPlanInCodedUnits) {
  std::string path = temp("l64.csv");
  Result r = run("oa --runs 64 --levels 3 --factors 14 --out " + path + " --report");
  ASSERT_EQ(r.code, 0) << r.err;
  demcal::Table t = demcal::Table::read_csv(path);
  EXPECT_EQ(t.rows(), 64u);
  EXPECT_EQ(t.cols(), 14u);
  EXPECT_EQ(t.names().front(), "x1");
  EXPECT_NE(r.out.find("| x1 | -1, 0, 1 | 32/16/16 |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("main effects orthogonal): yes"), std::string::npos);
}

TEST(DemcalDoe, ConcreteStudyDesignsInNaturalUnitsFromTheShippedSpaces) {
  std::string l64 = temp("l64.h5");
  std::remove(l64.c_str());
  Result r = run("oa --space " + data("spaces/su2021_concrete.json") + " --runs 64 --blank 1 --out " + l64);
  ASSERT_EQ(r.code, 0) << r.err;
  demcal::Table t = demcal::Table::read(l64, "/design");
  EXPECT_EQ(t.rows(), 64u);
  EXPECT_TRUE(t.has_column("pb_sigma_c_MPa"));
  EXPECT_TRUE(t.has_column("pb_sigma_c_MPa_coded"));
  EXPECT_TRUE(t.has_column("blank1"));
  EXPECT_EQ(t.attributes().at("kind"), "oa");

  std::string ccd = temp("ccd.csv");
  ASSERT_EQ(run("ccd --space " + data("spaces/su2021_ccd_sigma_u.json") + " --out " + ccd).code, 0);
  EXPECT_EQ(demcal::Table::read_csv(ccd).rows(), 13u);
  std::string bbd = temp("bbd.csv");
  ASSERT_EQ(run("bbd --space " + data("spaces/su2021_bbd_E.json") + " --out " + bbd).code, 0);
  EXPECT_EQ(demcal::Table::read_csv(bbd).rows(), 46u);
  ASSERT_EQ(run("bbd --space " + data("spaces/su2021_bbd_nu.json") + " --out " + bbd).code, 0);
  EXPECT_EQ(demcal::Table::read_csv(bbd).rows(), 27u);
}

TEST(DemcalDoe, SameSeedSameFile) {
  std::string a = temp("a.csv"), b = temp("b.csv");
  ASSERT_EQ(run("lhs --factors 3 --runs 20 --criterion phip --seed 9 --out " + a).code, 0);
  ASSERT_EQ(run("lhs --factors 3 --runs 20 --criterion phip --seed 9 --out " + b).code, 0);
  EXPECT_EQ(slurp(a), slurp(b));
  ASSERT_EQ(run("sobol --factors 3 --runs 16 --seed 9 --out " + b).code, 0);
  EXPECT_NE(slurp(a), slurp(b));
}

TEST(DemcalDoe, EveryKindRuns) {
  for (const char* args : {"oa --runs 18 --levels 2^1,3^7", "fullfact --factors 3 --levels 2,3,4",
                           "fracfact --factors 7 --runs 16", "fracfact --factors 5 --generators E=ABCD",
                           "pb --factors 11", "ccd --factors 3 --alpha orthogonal --center 4",
                           "ccd --factors 2 --type faced", "bbd --factors 6", "lhs --factors 4 --runs 30 --criterion maximin",
                           "sobol --factors 4 --runs 32"}) {
    Result r = run(std::string(args) + " --out " + temp("any.csv") + " --report");
    EXPECT_EQ(r.code, 0) << args << ": " << r.err;
    EXPECT_NE(r.out.find("## Design:"), std::string::npos) << args;
  }
}

TEST(DemcalDoe, BadInputGivesOneLineAndNonZeroExit) {
  std::string out = " --out " + temp("bad.csv");
  expect_one_line_error(run("cube --factors 3" + out), "unknown design kind \"cube\"");
  expect_one_line_error(run("bbd --factors 2" + out), "Box-Behnken designs need 3..7 factors");
  expect_one_line_error(run("ccd --factors 2 --alpha 0" + out), "--alpha must be positive");
  expect_one_line_error(run("ccd --factors 2 --alpha -1.4" + out), "--alpha must be positive");
  expect_one_line_error(run("oa --runs 10 --levels 3 --factors 3" + out), "no orthogonal array with 10 runs");
  expect_one_line_error(run("lhs --factors 2 --runs 8 --alpha 2" + out), "option --alpha does not apply to lhs");
  expect_one_line_error(run("oa --runs 9 --levels 3" + out), "give --space FILE.json or --factors N");
  expect_one_line_error(run("ccd --space /nonexistent/space.json" + out), "/nonexistent/space.json: cannot open");

  std::string space = temp("space.json");
  std::ofstream(space) << R"({"parameters": [{"name": "a", "low": 5, "high": 1}, {"name": "b", "low": 0, "high": 1}]})";
  expect_one_line_error(run("ccd --space " + space + out), "parameters[0] (\"a\"): low (5) must be below high (1)");
  expect_one_line_error(run("ccd --factors 2"), "--out is required");
}

TEST(DemcalDoeCli, ListsEveryKindWithItsOptionsAndFactorLimits) {
  Result r = run("--list-kinds");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json kinds = nlohmann::json::parse(r.out).at("kinds");
  for (const char* kind : {"oa", "fullfact", "fracfact", "pb", "ccd", "bbd", "lhs", "sobol"})
    EXPECT_TRUE(kinds.contains(kind)) << kind;
  // The listing is what the executable enforces: factor limits ...
  EXPECT_EQ(kinds["bbd"]["min_factors"], 3);
  EXPECT_EQ(kinds["bbd"]["max_factors"], 7);
  EXPECT_EQ(kinds["ccd"]["max_factors"], 10);
  EXPECT_TRUE(kinds["lhs"]["max_factors"].is_null());
  const std::string out = " --out " + temp("limits.csv");
  EXPECT_EQ(run("bbd --factors 7" + out).code, 0);
  expect_one_line_error(run("bbd --factors 8" + out), "Box-Behnken designs need 3..7 factors (got 8)");
  EXPECT_EQ(run("ccd --factors 10 --center 1" + out).code, 0);
  expect_one_line_error(run("ccd --factors 11" + out), "central composite designs need 2..10 factors (got 11)");
  expect_one_line_error(run("fracfact --factors 1" + out), "fractional factorial designs need 2..25 factors");
  // ... and run limits: an LHS needs at least 2 runs.
  EXPECT_EQ(kinds["lhs"]["min_runs"], 2);
  EXPECT_EQ(run("lhs --factors 2 --runs 2" + out).code, 0);
  expect_one_line_error(run("lhs --factors 2 --runs 1" + out), "at least 2");
}

// A circumscribed CCD's axial points may leave the space's box, but not make a
// modulus, a stiffness ratio or a friction negative: refused, every such
// parameter named on its own line with the fix, and nothing written.
TEST(DemcalDoe, RefusesADesignThatLeavesThePhysicalRange) {
  const std::string out = temp("unphysical.csv");
  std::remove(out.c_str());
  const Result r = run("ccd --space " + data("spaces/su2021_bbd_E.json") + " --out " + out);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("demcal-doe: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("the ccd design leaves the physical range of 5 parameter(s)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\n  Ec_GPa = -3.78"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(a stress cannot be negative)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\n  kn_ks = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("fix: --type inscribed or --type faced"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(out).good()) << "a refused design must write nothing";
  // The fix named works, and axial points inside the box are fine.
  EXPECT_EQ(run("ccd --space " + data("spaces/su2021_bbd_E.json") + " --type inscribed --out " + out).code, 0);
  EXPECT_EQ(run("ccd --space " + data("spaces/su2021_ccd_sigma_u.json") + " --out " + out).code, 0);
}

// With --scene, a design is held to the scene's declared bounds too (here a
// restitution coefficient above the heap scene's 1.0); without it, that
// dimensionless parameter has no upper limit to check.
TEST(DemcalDoe, SceneBoundsAreCheckedWhenASceneIsGiven) {
  const std::string space = temp("restitution_space.json"), out = temp("restitution.csv");
  std::ofstream(space) << R"({"parameters": [{"name": "e_pp", "unit": "1", "low": 0.2, "high": 0.9},
                                             {"name": "mu_pp", "unit": "1", "low": 0.3, "high": 0.75}]})";
  const std::string args = "ccd --space " + space + " --out " + out;
  EXPECT_EQ(run(args).code, 0);
  const Result r = run(args + " --scene " + data("scenes/heap_powder.json"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("e_pp = 1.04"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("above 1 (the scene's physical high)"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("mu_pp"), std::string::npos) << r.err;
  expect_one_line_error(run("ccd --factors 2 --scene " + data("scenes/heap_powder.json") + " --out " + out),
                        "--scene checks a design in natural units: give --space too");
}

// A point meant to lie on a bound lies on it exactly: mid - half misses
// 0.1 by rounding (0.3 - 0.2 = 0.09999999999999998).
TEST(DemcalDoe, PointsOnABoundLieOnItExactly) {
  const std::string out = temp("faced.csv");
  ASSERT_EQ(run("ccd --space " + data("spaces/he2019_powder.json") + " --type faced --out " + out).code, 0);
  const demcal::Table t = demcal::Table::read(out);
  const std::vector<double>& e = t.column("e_pp");
  EXPECT_EQ(*std::min_element(e.begin(), e.end()), 0.1);
  EXPECT_EQ(*std::max_element(e.begin(), e.end()), 0.5);
  const std::vector<double>& mu = t.column("mu_pp");
  EXPECT_EQ(*std::min_element(mu.begin(), mu.end()), 0.3);
  EXPECT_EQ(*std::max_element(mu.begin(), mu.end()), 0.75);
}
