// demcal-dem batch beyond one process tree: over MPI ranks (rank 0 hands out
// points and writes the one result file) and as shards of a job array joined
// by demcal-dem merge. Both must give exactly the serial batch's results.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "../common/command.hpp"

namespace {

using demcal::test::run_command;
using demcal::test::slurp;
using demcal::test::temp_path;

const std::string kBin = std::string(DEMCAL_BIN_DIR) + "/demcal-dem";
const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
// Open MPI's runtime leaks at MPI_Finalize (in plugins it has unloaded before
// LeakSanitizer reports, so no suppression can name them): under `make
// sanitize` the ranks run without leak checking; every other ASan check stays.
const std::string kMpirun = "mpirun --oversubscribe --allow-run-as-root -x ASAN_OPTIONS=detect_leaks=0";

std::string write_design(const std::string& name, int runs) {
  std::string path = temp_path(name);
  std::ofstream out(path);
  out << "run,pb_sigma_c_MPa,pb_tau_c_MPa\n";
  for (int r = 1; r <= runs; ++r) out << r << "," << 8 + r << "," << 20 + 2 * r << "\n";
  return path;
}

std::string batch_args(const std::string& design, const std::string& name) {
  return " batch --scene " + kScene + " --design " + design + " --out " + temp_path(name + ".h5") + " --csv " +
         temp_path(name + ".csv") + " --seeds 2 --cache " + temp_path("cache_" + name);
}

// The serial batch's CSV, computed once for the tests that compare with it.
const std::string& serial_csv(const std::string& design) {
  static std::string csv;
  if (csv.empty()) {
    auto r = run_command(kBin + batch_args(design, "serial") + " --jobs 2 --quiet", "serial");
    EXPECT_EQ(r.code, 0) << r.err;
    csv = slurp(temp_path("serial.csv"));
  }
  return csv;
}

TEST(DemcalDemMpiBatch, TwoRanksGiveTheSerialResult) {
  const std::string design = write_design("design.csv", 4);
  const std::string& serial = serial_csv(design);
  ASSERT_EQ(std::count(serial.begin(), serial.end(), '\n'), 9) << serial;  // header + 4 runs x 2 seeds
  auto r = run_command(kMpirun + " -np 2 " + kBin + batch_args(design, "mpi2") + " --quiet", "mpi2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(temp_path("mpi2.csv")), serial);
}

TEST(DemcalDemMpiBatch, ThreeRanksGiveTheSerialResultAndARerunRunsNothing) {
  const std::string design = write_design("design.csv", 4);
  const std::string& serial = serial_csv(design);
  auto r = run_command(kMpirun + " -np 3 " + kBin + batch_args(design, "mpi3"), "mpi3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(temp_path("mpi3.csv")), serial);
  EXPECT_NE(r.err.find("8 point(s) over 2 worker rank(s)"), std::string::npos) << r.err;

  auto again = run_command(kMpirun + " -np 3 " + kBin + batch_args(design, "mpi3"), "mpi3_again");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("8 points: 8 ok, 0 failed, 8 done before"), std::string::npos) << again.err;
}

TEST(DemcalDemMpiBatch, ABadDesignIsOneErrorLineFromRankZero) {
  auto r = run_command(kMpirun + " -np 2 " + kBin + batch_args(temp_path("missing.csv"), "mpi_bad"), "mpi_bad");
  EXPECT_NE(r.code, 0);
  const std::string marker = "demcal-dem: error: ";
  const auto first = r.err.find(marker);
  ASSERT_NE(first, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(marker, first + 1), std::string::npos) << "more than one rank reported it:\n" << r.err;
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos) << r.err;
}

TEST(DemcalDemShards, ShardsMergedGiveTheSerialResultAndTheMergeResumes) {
  const std::string design = write_design("design.csv", 4);
  const std::string& serial = serial_csv(design);
  for (const std::string shard : {"1/3", "2/3", "3/3"}) {
    const std::string name = "shard" + shard.substr(0, 1);
    auto r = run_command(kBin + batch_args(design, name) + " --shard " + shard + " --quiet", name);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  // Every third point: shard 1 holds points 1, 4, 7 of the 8.
  const std::string first = slurp(temp_path("shard1.csv"));
  EXPECT_EQ(std::count(first.begin(), first.end(), '\n'), 4) << first;

  const std::string merged = temp_path("merged.h5"), merged_csv = temp_path("merged.csv");
  auto m = run_command(kBin + " merge " + temp_path("shard1.h5") + " " + temp_path("shard2.h5") + " " +
                           temp_path("shard3.h5") + " --out " + merged + " --csv " + merged_csv,
                       "merge");
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(slurp(merged_csv), serial);

  // A batch over the whole design into the merged file has nothing left to run.
  auto resume = run_command(kBin + " batch --scene " + kScene + " --design " + design + " --out " + merged +
                                " --seeds 2 --cache " + temp_path("cache_merged"),
                            "merge_resume");
  ASSERT_EQ(resume.code, 0) << resume.err;
  EXPECT_NE(resume.err.find("8 points: 8 ok, 0 failed, 8 done before"), std::string::npos) << resume.err;
}

TEST(DemcalDemShards, AMissingShardIsReportedAndABatchFillsItIn) {
  const std::string design = write_design("design.csv", 4);
  const std::string& serial = serial_csv(design);
  for (const std::string shard : {"1/2", "2/2"}) {
    const std::string name = "half" + shard.substr(0, 1);
    auto r = run_command(kBin + batch_args(design, name) + " --shard " + shard + " --quiet", name);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const std::string merged = temp_path("partial.h5");
  auto m = run_command(kBin + " merge " + temp_path("half1.h5") + " --out " + merged + " --csv " + temp_path("partial.csv"),
                       "partial_merge");
  EXPECT_EQ(m.code, 4) << m.err;
  EXPECT_NE(m.err.find("4 of the design's 8 points are missing"), std::string::npos) << m.err;
  auto fill = run_command(kBin + " batch --scene " + kScene + " --design " + design + " --out " + merged + " --csv " +
                              temp_path("filled.csv") + " --seeds 2 --cache " + temp_path("cache_fill"),
                          "fill");
  ASSERT_EQ(fill.code, 0) << fill.err;
  EXPECT_NE(fill.err.find("resuming: 4 of 8 points already done"), std::string::npos) << fill.err;
  EXPECT_EQ(slurp(temp_path("filled.csv")), serial);
}

TEST(DemcalDemShards, BadShardsAreOneLineErrors) {
  const std::string design = write_design("design_small.csv", 1);
  for (const std::string shard : {"0/2", "3/2", "2", "a/b", "1/2x"}) {
    auto r = run_command(kBin + batch_args(design, "bad_shard") + " --shard " + shard, "bad_shard");
    demcal::test::expect_one_line_error(r, "demcal-dem", "--shard");
  }
}

TEST(DemcalDemShards, MergingDifferentResultsForOneRunIsAnError) {
  // The same design file, edited between two batches: run 1 means two different points.
  const std::string design = temp_path("conflict.csv");
  for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{{"conflict_a", "9"},
                                                                                             {"conflict_b", "12"}}) {
    std::ofstream(design) << "run,pb_sigma_c_MPa\n1," << value << "\n";
    auto r = run_command(kBin + " batch --scene " + kScene + " --design " + design + " --out " + temp_path(name + ".h5") +
                             " --cache " + temp_path("cache_conflict") + " --quiet",
                         name);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  auto m = run_command(kBin + " merge " + temp_path("conflict_a.h5") + " " + temp_path("conflict_b.h5") + " --out " +
                           temp_path("conflict.h5"),
                       "conflict_merge");
  demcal::test::expect_one_line_error(m, "demcal-dem", "run 1 seed 1 differs between");

  // Files of two different designs do not merge either.
  const std::string other = temp_path("other_design.csv");
  std::ofstream(other) << "run,pb_sigma_c_MPa\n2,10\n";
  auto r = run_command(kBin + " batch --scene " + kScene + " --design " + other + " --out " + temp_path("other.h5") +
                           " --cache " + temp_path("cache_conflict") + " --quiet",
                       "other");
  ASSERT_EQ(r.code, 0) << r.err;
  auto mixed = run_command(kBin + " merge " + temp_path("conflict_a.h5") + " " + temp_path("other.h5") + " --out " +
                               temp_path("mixed.h5"),
                           "mixed_merge");
  demcal::test::expect_one_line_error(mixed, "demcal-dem", "was run on design");
}

}  // namespace
