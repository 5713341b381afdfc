// The peer run of make bench as users call it: `demcal-dem export --lammps`
// writes the packed specimen exactly, and `demcal-dem released` turns its
// locked-in overlaps into motion. Without friction or damping, once every
// contact has opened the kinetic energy is the springs' initial energy,
// 1/2 kn sum(overlap^2) over the exported disks (a closed form of energy
// conservation that also checks the export).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../common/lammps_atoms.hpp"
#include "../common/scratch.hpp"

namespace {

int run(const std::string& arguments, const std::string& stdout_path) {
  const std::string command = std::string(DEMCAL_BIN_DIR) + "/demcal-dem " + arguments + " --quiet --cache " +
                              demcal::test::scratch_path("cache") + " >" + stdout_path + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(ReleasedRun, FrictionlessReleaseTurnsTheSpringEnergyOfTheExportedSpecimenIntoMotion) {
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  const std::string data = demcal::test::scratch_path("specimen.data"), log = demcal::test::scratch_path("export.txt");
  ASSERT_EQ(run("export --scene " + scene + " --seed 1 --lammps " + data, log), 0);
  std::size_t declared = 0;
  const std::vector<demcal::test::LammpsAtom> disks = demcal::test::read_lammps_atoms(data, declared);
  ASSERT_GT(disks.size(), 200u);
  EXPECT_EQ(disks.size(), declared);

  const double kn = 1e8;
  double spring_energy_j = 0;
  for (std::size_t i = 0; i < disks.size(); ++i)
    for (std::size_t j = i + 1; j < disks.size(); ++j) {
      const double overlap = 0.5 * disks[i].diameter + 0.5 * disks[j].diameter -
                             std::hypot(disks[j].x - disks[i].x, disks[j].y - disks[i].y);
      if (overlap > 0) spring_energy_j += 0.5 * kn * overlap * overlap;
    }
  ASSERT_GT(spring_energy_j, 0.0) << "genesis leaves overlaps, so the release has energy to give";

  const std::string out = demcal::test::scratch_path("released.json");
  ASSERT_EQ(run("released --scene " + scene + " --seed 1 --kn 1e8 --ks 5e7 --friction 0 --dt 5e-8 --steps 20000 "
                "--every 2000 --threads 1",
                out),
            0);
  nlohmann::json result;
  std::ifstream(out) >> result;
  EXPECT_EQ(result.at("disks").get<std::size_t>(), disks.size());
  EXPECT_EQ(result.at("steps"), 20000);
  EXPECT_GT(result.at("particle_steps_per_s").get<double>(), 0.0);
  const auto& last = result.at("history").back();
  ASSERT_EQ(last.at(0), 20000);
  const double kinetic_j = last.at(1).get<double>() + last.at(2).get<double>();
  // dt is a few percent of sqrt(m / kn) here: central differences keep the energy to 1e-4.
  EXPECT_NEAR(kinetic_j, spring_energy_j, 1e-4 * spring_energy_j);
}

TEST(ReleasedRun, ATimeStepIsRequired) {
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";
  const std::string out = demcal::test::scratch_path("no_dt.txt");
  EXPECT_NE(run("released --scene " + scene + " --steps 10", out), 0);
  EXPECT_NE(run("released --scene " + scene + " --dt -1 --steps 10", out), 0);
}
