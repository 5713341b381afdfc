// demcal-dem run as users call it: a result file, and one-line errors.
#include <gtest/gtest.h>

#include "../common/lammps_atoms.hpp"
#include "../common/scratch.hpp"

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace {

struct Result {
  int code;
  std::string err;
};

std::string temp(const std::string& name) {
  return demcal::test::scratch_path(name);
}

Result run(const std::string& arguments) {
  std::string err = temp("stderr");
  std::string command = std::string(DEMCAL_BIN_DIR) + "/demcal-dem " + arguments + " --quiet --cache " + temp("cache") +
                        " >/dev/null 2>" + err;
  int status = std::system(command.c_str());
  std::ifstream in(err);
  std::stringstream s;
  s << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str()};
}

const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small.json";

}  // namespace

TEST(DemcalDem, RunWritesTheResultFile) {
  std::string out = temp("result.json"), curve = temp("curve.csv");
  Result r = run("run --scene " + kScene + " --set pb_sigma_c_MPa=12 --seed 2 --out " + out + " --curve " + curve);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json result;
  std::ifstream(out) >> result;
  EXPECT_EQ(result.at("status"), "ok");
  EXPECT_EQ(result.at("seed"), 2);
  EXPECT_EQ(result.at("parameters").at("pb_sigma_c_MPa"), 12.0);
  for (const char* key : {"sigma_u_MPa", "E_GPa", "nu", "E50_GPa", "peak_strain", "cracks_tension", "cracks_shear"})
    EXPECT_TRUE(result.at("macro").contains(key)) << key;
  EXPECT_GT(result.at("particles").get<int>(), 200);
  EXPECT_GT(result.at("particle_steps_per_s").get<double>(), 0.0);
  std::ifstream curve_file(curve);
  std::string header;
  std::getline(curve_file, header);
  EXPECT_EQ(header, "run,axial_strain,stress_MPa,lateral_strain,cracks");
}

// stdout is where the result goes without --out, --quiet or not; with --out
// and --quiet, stdout stays empty.
TEST(DemcalDem, RunPrintsTheResultOnStdoutWithoutOut) {
  const std::string printed = temp("printed.json"), printed_too = temp("printed_too.json");
  const std::string base =
      std::string(DEMCAL_BIN_DIR) + "/demcal-dem run --scene " + kScene + " --seed 3 --quiet --cache " + temp("cache");
  ASSERT_EQ(std::system((base + " >" + printed + " 2>/dev/null").c_str()), 0);
  nlohmann::json result;
  std::ifstream(printed) >> result;
  EXPECT_EQ(result.at("status"), "ok");
  EXPECT_EQ(result.at("seed"), 3);
  const std::string with_out = base + " --out " + temp("printed_out.json") + " >" + printed_too + " 2>/dev/null";
  ASSERT_EQ(std::system(with_out.c_str()), 0);
  std::ifstream quiet(printed_too);
  EXPECT_EQ(quiet.peek(), std::ifstream::traits_type::eof());
}

TEST(DemcalDem, VtkSnapshotsHoldTheDisksBondsAndBreaks) {
  std::string dir = temp("vtk");
  Result r = run("run --scene " + kScene + " --out " + temp("vtk.json") + " --vtk " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json result;
  std::ifstream(temp("vtk.json")) >> result;
  std::ifstream first(dir + "/disks_000001.vtk");
  ASSERT_TRUE(first.good());
  std::string text((std::istreambuf_iterator<char>(first)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("# vtk DataFile Version 3.0", 0), 0u);
  EXPECT_NE(text.find("POINTS " + std::to_string(result.at("particles").get<int>()) + " double"), std::string::npos);
  EXPECT_NE(text.find("SCALARS radius double 1"), std::string::npos);
  EXPECT_NE(text.find("VECTORS velocity double"), std::string::npos);
  // The final breaks file (named by the number of curve points) lists every bond break of the run.
  const int breaks = static_cast<int>(result.at("macro").at("cracks_tension").get<double>() +
                                      result.at("macro").at("cracks_shear").get<double>());
  bool found = false;
  for (int points = 1; points < 100000 && !found; ++points) {
    char name[64];
    std::snprintf(name, sizeof(name), "/final_breaks_%06d.vtk", points);
    std::ifstream f(dir + name);
    if (!f.good()) continue;
    found = true;
    std::string content((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_NE(content.find("POINTS " + std::to_string(breaks) + " double"), std::string::npos) << content.substr(0, 200);
  }
  EXPECT_TRUE(found);
}

TEST(DemcalDem, BadInputIsOneLineAndNonZero) {
  std::string out = " --out " + temp("bad.json");
  for (auto [args, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"run --scene " + kScene + " --set Ec=3", "unknown parameter \"Ec\""},
           {"run --scene " + kScene + " --set Ec_GPa=0", "Ec_GPa = 0 lies outside [0.1, 500]"},
           {"run --scene " + kScene + " --set Ec_GPa=nan", "not a finite number"},
           {"run --scene " + kScene + " --set Ec_GPa", "expected NAME=VALUE"},
           {"run --scene /nonexistent.json", "cannot open scene file"}}) {
    Result r = run(args + out);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  }
}

// A run that fails says why on stderr, --quiet and --out or not, and exits 4
// (the reason is in the result file too).
TEST(DemcalDem, AFailedRunSaysWhyOnStderr) {
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/external_fake.json";
  const std::string out = temp("failed_run.json");
  Result r = run("run --scene " + scene + " --set mode=1 --out " + out);
  EXPECT_EQ(r.code, 4);
  EXPECT_EQ(r.err.rfind("demcal-dem: error: the run failed: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("(recorded in " + out + ")"), std::string::npos) << r.err;
  nlohmann::json result;
  std::ifstream(out) >> result;
  EXPECT_EQ(result.at("status"), "failed");
  EXPECT_NE(r.err.find(result.at("reason").get<std::string>()), std::string::npos) << r.err;
}

// A 3D scene's packing for the peers: YADE's x y z r lines and a 3D LAMMPS
// data file, the same spheres in the same order, inside the scene's cylinder.
TEST(DemcalDem, ExportWritesA3DSceneForYadeAndLammps) {
  const std::string scene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/ucs_small_3d.json";
  const std::string text = temp("spheres.txt"), data = temp("spheres.data");
  Result r = run("export --scene " + scene + " --yade " + text + " --lammps " + data);
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<std::array<double, 4>> spheres;  // x y z r
  std::ifstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::array<double, 4> s{};
    std::istringstream fields(line);
    for (double& v : s) ASSERT_TRUE(fields >> v) << line;
    spheres.push_back(s);
  }
  ASSERT_GT(spheres.size(), 200u);
  for (const auto& s : spheres) {  // the scene's cylinder: D 10 mm, H 20 mm; radii 0.6-0.9 mm scaled to the porosity
    EXPECT_LE(std::hypot(s[0], s[1]) + s[3], 0.005 * 1.01);
    EXPECT_GT(s[3], 0.0);
    EXPECT_GE(s[2] - s[3], -0.0001);
    EXPECT_LE(s[2] + s[3], 0.0201);
  }
  // The LAMMPS file: as many atoms, each the text file's sphere (diameter, then x y z last) to the last digit.
  std::size_t declared = 0;
  const std::vector<demcal::test::LammpsAtom> atoms = demcal::test::read_lammps_atoms(data, declared);
  EXPECT_EQ(declared, spheres.size());
  ASSERT_EQ(atoms.size(), spheres.size());
  for (std::size_t k = 0; k < atoms.size(); ++k) {
    EXPECT_EQ(atoms[k].x, spheres[k][0]);
    EXPECT_EQ(atoms[k].z, spheres[k][2]);
    EXPECT_EQ(atoms[k].diameter, 2 * spheres[k][3]);
  }
}

TEST(DemcalDem, ExportRefusesYadeForA2DSceneAndNoOutput) {
  Result r = run("export --scene " + kScene + " --yade " + temp("disks.txt"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--yade"), std::string::npos) << r.err;
  r = run("export --scene " + kScene);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--lammps FILE or --yade FILE"), std::string::npos) << r.err;
}
