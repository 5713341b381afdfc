// demcal-dem batch: every point of a design, several seeds, results as soon as
// they are done; killed with SIGKILL and rerun, it loses and repeats nothing
// that had finished.
#include <gtest/gtest.h>

#include "../common/scratch.hpp"

#include <dirent.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/table.hpp"
#include "demcal/jobs/batch.hpp"
#include "demcal/jobs/point_store.hpp"

namespace {

std::string temp(const std::string& name) {
  return demcal::test::scratch_path(name);
}

std::map<std::string, std::string> point_files(const std::string& dir) {
  std::map<std::string, std::string> files;
  if (DIR* d = ::opendir(dir.c_str())) {
    while (dirent* e = ::readdir(d)) {
      std::string name = e->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".json") {
        std::ifstream in(dir + "/" + name);
        std::stringstream s;
        s << in.rdbuf();
        files[name] = s.str();
      }
    }
    ::closedir(d);
  }
  return files;
}

const std::string kBin = std::string(DEMCAL_BIN_DIR) + "/demcal-dem";
const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";

std::string write_design(int runs) {
  std::string path = temp("design.csv");
  std::ofstream out(path);
  out << "run,pb_sigma_c_MPa,pb_tau_c_MPa,pb_sigma_c_MPa_coded\n";
  for (int r = 1; r <= runs; ++r) out << r << "," << 8 + r << "," << 20 + 2 * r << ",0\n";
  return path;
}

}  // namespace

TEST(DemcalDemBatch, KilledAndRerunItRepeatsNoFinishedPoint) {
  const std::string design = write_design(5), out = temp("responses.h5"), csv = temp("responses.csv");
  const std::string cache = temp("cache");
  std::vector<std::string> args = {kBin, "batch", "--scene", kScene, "--design", design, "--out", out,
                                   "--seeds", "2", "--jobs", "1", "--csv", csv, "--cache", cache, "--quiet"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  // Kill it once a few points are done, while others are still to come.
  const auto start = std::chrono::steady_clock::now();
  while (point_files(out + ".points").size() < 3 && std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // workers die with the batch
  auto before = point_files(out + ".points");
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), 10u) << "the batch finished before it could be killed";

  std::string command;
  for (std::size_t i = 0; i + 1 < args.size(); ++i) command += args[i] + " ";
  ASSERT_EQ(std::system((command + "--quiet 2>/dev/null").c_str()), 0);
  auto after = point_files(out + ".points");
  ASSERT_EQ(after.size(), 10u);
  for (const auto& [name, content] : before) EXPECT_EQ(after.at(name), content) << name << " was run again";

  // The responses file and the CSV export hold every point.
  demcal::h5::File file(out, demcal::h5::Mode::ReadOnly);
  EXPECT_EQ(file.group("/points", false).children().size(), 10u);
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("run,pb_sigma_c_MPa,pb_tau_c_MPa,seed,status,", 0), 0u) << header;
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_NE(line.find(",ok,"), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 10);
}

TEST(DemcalDemBatch, ABadDesignPointIsRecordedAsFailedAndTheBatchGoesOn) {
  std::string design = temp("bad_design.csv"), out = temp("bad.h5"), csv = temp("bad.csv");
  std::ofstream(design) << "run,pb_sigma_c_MPa,Ec_GPa\n1,10,16\n2,10,-5\n3,12,16\n";
  std::string command = kBin + " batch --scene " + kScene + " --design " + design + " --out " + out + " --csv " + csv +
                        " --cache " + temp("cache") + " --quiet 2>/dev/null";
  int status = std::system(command.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 4);  // some points failed
  std::ifstream in(csv);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("2,10,-5,1,failed: parameter Ec_GPa = -5 lies outside [0.1; 500]"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4);
  EXPECT_NE(text.find("\n3,12,16,1,ok,"), std::string::npos) << text;
}

TEST(DemcalDemBatch, AChangedDesignPointIsRunAgainNotReused) {
  const std::string out = temp("changed.h5"), cache = temp("cache_changed");
  auto batch = [&](const std::string& design) {
    std::string command = kBin + " batch --scene " + kScene + " --design " + design + " --out " + out + " --jobs 2 --cache " +
                          cache + " --quiet 2>" + temp("changed.err");
    return std::system(command.c_str());
  };
  const std::string design = temp("changed_design.csv");
  {
    std::ofstream(design) << "run,pb_sigma_c_MPa\n1,9\n2,11\n";
  }
  ASSERT_EQ(batch(design), 0);
  std::map<std::string, std::string> before = point_files(out + ".points");
  {
    std::ofstream(design) << "run,pb_sigma_c_MPa\n1,9\n2,14\n";  // run 2 now means something else
  }
  ASSERT_EQ(batch(design), 0);
  std::map<std::string, std::string> after = point_files(out + ".points");
  EXPECT_EQ(after.at("run1_seed1.json"), before.at("run1_seed1.json"));  // unchanged: reused
  EXPECT_NE(after.at("run2_seed1.json"), before.at("run2_seed1.json"));  // changed: run again
  EXPECT_NE(after.at("run2_seed1.json").find("\"pb_sigma_c_MPa\":14.0"), std::string::npos) << after.at("run2_seed1.json");
}

TEST(DemcalDemBatch, AnEditedSceneIsRunAgainNotReused) {
  // A stored result carries the fingerprint of the scene it was made on.
  const std::string out = temp("edited.h5"), cache = temp("cache_edited"), scene = temp("edited_scene.json");
  std::string text;
  {
    std::ifstream in(kScene);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  std::ofstream(scene) << text;
  const std::string design = temp("edited_design.csv");
  std::ofstream(design) << "run,pb_sigma_c_MPa\n1,9\n";
  auto batch = [&]() {
    return std::system((kBin + " batch --scene " + scene + " --design " + design + " --out " + out + " --cache " + cache +
                        " --quiet 2>/dev/null")
                           .c_str());
  };
  ASSERT_EQ(batch(), 0);
  const std::string first = point_files(out + ".points").at("run1_seed1.json");
  ASSERT_EQ(batch(), 0);
  EXPECT_EQ(point_files(out + ".points").at("run1_seed1.json"), first);  // same scene: reused

  const auto at = text.find("\"stop_fraction_of_peak\": 0.7");
  ASSERT_NE(at, std::string::npos);
  std::ofstream(scene) << text.replace(at, 28, "\"stop_fraction_of_peak\": 0.5");
  ASSERT_EQ(batch(), 0);
  EXPECT_NE(point_files(out + ".points").at("run1_seed1.json"), first);  // edited scene: run again
}

TEST(DemcalDemBatch, ADesignColumnThatNamesNoSceneParameterIsAnError) {
  // A typo would otherwise run every point at the scene's default.
  const std::string design = temp("typo_design.csv"), err = temp("typo.err");
  std::ofstream(design) << "run,pb_sigma_c_MPa,pb_sigma_c_MPa_coded,Ec_GPA,blank1,null_column\n1,10,0,16,1,2\n";
  const int status = std::system((kBin + " batch --scene " + kScene + " --design " + design + " --out " +
                                  temp("typo.h5") + " --cache " + temp("cache") + " --quiet 2>" + err)
                                     .c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(err);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(design + ": column \"Ec_GPA\" is not a parameter of the scene"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
}

TEST(DesignPoints, ReplicatedRowsRunOnOtherSpecimens) {
  // Rows 2 and 4 repeat row 1 (a design's centre replicates): with 2 seeds per
  // row, row 1 takes seeds 1-2, row 2 seeds 3-4, row 4 seeds 5-6; row 3 occurs
  // once and keeps seeds 1-2, as every row did before replicates were told apart.
  demcal::Table design(std::vector<int>{1, 2, 3, 4});
  design.add_column("a", {0.5, 0.5, 0.7, 0.5});
  design.add_column("b", {2.0, 2.0, 2.0, 2.0});
  const auto points = demcal::jobs::design_points(design, {"a", "b"}, 2, "/tmp/p", "fp", 1);
  ASSERT_EQ(points.size(), 8u);
  std::vector<std::pair<int, std::uint64_t>> got;
  for (const auto& p : points) got.push_back({p.run, p.seed});
  const std::vector<std::pair<int, std::uint64_t>> want = {{1, 1}, {1, 2}, {2, 3}, {2, 4}, {3, 1}, {3, 2}, {4, 5}, {4, 6}};
  EXPECT_EQ(got, want);
  EXPECT_EQ(points[2].file, "/tmp/p/run2_seed3.json");
  EXPECT_EQ(points[4].design.at("a"), 0.7);
}

TEST(DemcalDemBatch, FewerPointsThanCoresShareTheCoresAndManyPointsGetOneEach) {
  // 5 seeds of a verification on 16 cores: 3 threads each, not 1.
  EXPECT_EQ(demcal::jobs::threads_per_run(16, 16, 5), 3);
  EXPECT_EQ(demcal::jobs::threads_per_run(16, 4, 40), 4);
  // As many points at once as cores: one thread each.
  EXPECT_EQ(demcal::jobs::threads_per_run(2, 2, 40), 1);
  // One point at a time gets the whole budget.
  EXPECT_EQ(demcal::jobs::threads_per_run(8, 1, 40), 8);
  EXPECT_EQ(demcal::jobs::threads_per_run(8, 3, 1), 8);
  // More points at once than threads: still one each.
  EXPECT_EQ(demcal::jobs::threads_per_run(2, 4, 40), 1);
}

TEST(DemcalDemBatch, ATestListRunsEveryTestPerPointAndResumes) {
  // tests_small.json: UCS, Brazilian and a two-confinement biaxial series of one material.
  const std::string list = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/tests_small.json";
  const std::string out = temp("list.h5"), csv = temp("list.csv"), cache = temp("cache_list");
  const std::string design = temp("list_design.csv");
  std::ofstream(design) << "run,pb_sigma_c_MPa\n1,9\n2,12\n";
  const std::string command = kBin + " batch --scene " + list + " --design " + design + " --out " + out + " --csv " +
                              csv + " --jobs 2 --cache " + cache + " --quiet 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::map<std::string, std::string> first = point_files(out + ".points");
  ASSERT_EQ(first.size(), 2u);
  const nlohmann::json point = nlohmann::json::parse(first.at("run1_seed1.json"));
  EXPECT_EQ(point.at("status"), "ok") << point.at("reason");
  EXPECT_EQ(point.at("test_runs"), 3);
  for (const char* name : {"sigma_u_MPa", "sigma_t_MPa", "q_peak_MPa_2", "phi_deg", "ucs.cracks_tension"})
    EXPECT_TRUE(point.at("macro").contains(name)) << name;
  // The CSV has a column per output of the set, and a rerun repeats nothing.
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find("sigma_t_MPa"), std::string::npos) << header;
  EXPECT_NE(header.find("brazilian.cracks_tension"), std::string::npos) << header;
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(point_files(out + ".points"), first);
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct BatchRun {
  int code;
  std::string err;
};

BatchRun batch_into(const std::string& scene, const std::string& design, const std::string& out,
                    const std::string& extra = "") {
  const std::string err = temp("batch_into.err");
  const int status = std::system((kBin + " batch --scene " + scene + " --design " + design + " --out " + out +
                                  " --cache " + temp("cache") + " --quiet " + extra + " 2>" + err)
                                     .c_str());
  return {WEXITSTATUS(status), read_text(err)};
}

}  // namespace

// A batch into an OUT that holds another scene's results is refused before
// anything is written, naming the stored scene; --move-aside moves the old
// results into OUT_STEM.moved-1/ (never deletes them) and runs.
TEST(DemcalDemBatch, AnotherScenesResultsAreRefusedOrMovedAsideNeverOverwritten) {
  const std::string out = temp("owned.h5"), design = temp("owned_design.csv"), other = temp("other_scene.json");
  std::ofstream(design) << "run,pb_sigma_c_MPa\n1,9\n";
  std::string text = read_text(kScene);
  text.replace(text.find("\"ucs_small\""), 11, "\"ucs_other\"");
  std::ofstream(other) << text;

  ASSERT_EQ(batch_into(kScene, design, out).code, 0);
  const std::string first = point_files(out + ".points").at("run1_seed1.json");
  EXPECT_NE(read_text(out + ".points/scene.owner").find("\"ucs_small\""), std::string::npos);

  const BatchRun refused = batch_into(other, design, out);
  EXPECT_EQ(refused.code, 2);
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_NE(refused.err.find("holds the results of another scene (scene \"ucs_small\" from " + kScene + ")"),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--move-aside"), std::string::npos) << refused.err;
  EXPECT_EQ(point_files(out + ".points").at("run1_seed1.json"), first);  // untouched

  const BatchRun moved = batch_into(other, design, out, "--move-aside");
  ASSERT_EQ(moved.code, 0) << moved.err;
  const std::string aside = temp("owned.moved-1");
  EXPECT_EQ(point_files(aside + "/owned.h5.points").at("run1_seed1.json"), first);
  EXPECT_TRUE(std::ifstream(aside + "/owned.h5").good());
  EXPECT_NE(read_text(out + ".points/scene.owner").find("\"ucs_other\""), std::string::npos);
  EXPECT_EQ(batch_into(other, design, out).code, 0);  // its own results: resumes

  // Scenes without a name of their own are told apart by their files.
  const std::string unnamed_a = temp("unnamed_a.json"), unnamed_b = temp("unnamed_b.json"), shared = temp("unnamed.h5");
  std::string plain = read_text(kScene);
  plain.erase(plain.find("\"name\": \"ucs_small\","), 20);
  std::ofstream(unnamed_a) << plain;
  std::ofstream(unnamed_b) << plain;
  ASSERT_EQ(batch_into(unnamed_a, design, shared).code, 0);
  EXPECT_NE(batch_into(unnamed_b, design, shared).err.find("holds the results of another scene (scene \"scene\""),
            std::string::npos);
}

// A failed point says so on stderr as it happens, with its reason, even with
// --quiet; the batch goes on and exits 4.
TEST(DemcalDemBatch, AFailedPointsReasonIsPrintedAsItHappens) {
  const std::string design = temp("failing_design.csv"), out = temp("failing.h5");
  std::ofstream(design) << "run,pb_sigma_c_MPa,Ec_GPa\n1,10,16\n2,10,-5\n";
  const BatchRun r = batch_into(kScene, design, out);
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("demcal-dem: warning: run 2 seed 1 failed: parameter Ec_GPa = -5 lies outside [0.1, 500]"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("run 1 seed 1"), std::string::npos) << r.err;
}

// A point stopped by a wall-clock limit (run.max_wall_s, loading.max_wall_s,
// an external command's timeout_s) failed because of the machine's load, not
// its physics: a resumed batch runs it again. A deterministic failure (a value
// out of bounds) stays as stored.
TEST(DemcalDemBatch, APointStoppedByAWallClockLimitRunsAgainOnResumeOthersFailuresStay) {
  const std::string design = temp("timeout_design.csv"), out = temp("timeout.h5");
  std::ofstream(design) << "run,pb_sigma_c_MPa,Ec_GPa\n1,10,16\n2,10,-5\n";
  ASSERT_EQ(batch_into(kScene, design, out).code, 4);
  const std::string first = out + ".points/run1_seed1.json", second = out + ".points/run2_seed1.json";
  nlohmann::json stored = nlohmann::json::parse(read_text(first));
  ASSERT_EQ(stored.at("status"), "ok");
  stored["status"] = "failed";
  stored["reason"] = "timeout: the ucs took longer than loading.max_wall_s 1 s";
  stored["macro"] = nlohmann::json::object();
  std::ofstream(first) << stored.dump();
  const std::string deterministic = read_text(second);
  const BatchRun again = batch_into(kScene, design, out);
  EXPECT_EQ(again.code, 4);  // run 2 still fails
  EXPECT_NE(again.err.find("1 stored point(s) failed at a wall-clock limit"), std::string::npos) << again.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(first)).at("status"), "ok");  // run again
  EXPECT_EQ(read_text(second), deterministic);                           // kept
}
