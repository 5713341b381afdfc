// What every stage executable owes a user: --version with the commit built,
// the exit codes under --help (and under each subcommand's --help).
#include <gtest/gtest.h>

#include "../common/command.hpp"

namespace {

using demcal::test::run_program;

const char* const kPrograms[] = {"demcal-doe", "demcal-dem", "demcal-analyze", "demcal-fit",
                                 "demcal-predict", "demcal-invert", "demcal-verify"};

TEST(EveryExecutable, VersionNamesTheProgramVersionAndCommit) {
  for (const char* program : kPrograms) {
    const auto r = run_program(program, "--version");
    EXPECT_EQ(r.code, 0) << program << ": " << r.err;
    EXPECT_EQ(r.out.rfind(std::string(program) + " 0.", 0), 0u) << program << ": " << r.out;
    EXPECT_NE(r.out.find("(commit "), std::string::npos) << program << ": " << r.out;
  }
}

TEST(EveryExecutable, HelpListsTheExitCodes) {
  for (const char* program : kPrograms) {
    const auto r = run_program(program, "--help");
    EXPECT_EQ(r.code, 0) << program;
    EXPECT_NE(r.out.find("Exit codes: 0 done; 2 bad input"), std::string::npos) << program << ": " << r.out;
  }
  // The program's own codes, and on a subcommand's help too.
  EXPECT_NE(run_program("demcal-invert", "--help").out.find("3 a target outside"), std::string::npos);
  const auto batch = run_program("demcal-dem", "batch --help");
  EXPECT_NE(batch.out.find("4 the run failed, a batch point failed"), std::string::npos) << batch.out;
  EXPECT_NE(batch.out.find("--move-aside"), std::string::npos) << batch.out;
}

}  // namespace
