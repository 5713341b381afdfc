#pragma once
// The atoms of a LAMMPS data file (atom_style sphere) as demcal-dem export
// writes them, for the tests that read an export back.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace demcal::test {

struct LammpsAtom {
  double diameter, density, x, y, z;
};

// Every row of the "Atoms # sphere" section, in file order (a row that does
// not read as id, type, diameter, density, x, y, z fails the test);
// `declared` gets the header's atom count.
inline std::vector<LammpsAtom> read_lammps_atoms(const std::string& path, std::size_t& declared) {
  std::ifstream in(path);
  std::string line;
  std::vector<LammpsAtom> atoms;
  bool in_atoms = false;
  declared = 0;
  while (std::getline(in, line)) {
    if (line.find(" atoms") != std::string::npos && !in_atoms) declared = std::stoul(line);
    if (line.rfind("Atoms # sphere", 0) == 0) {
      in_atoms = true;
      continue;
    }
    if (!in_atoms || line.empty()) continue;
    std::istringstream fields(line);
    double id, type;
    LammpsAtom a{};
    if (!(fields >> id >> type >> a.diameter >> a.density >> a.x >> a.y >> a.z)) {
      ADD_FAILURE() << path << ": not an atom row: " << line;
      continue;
    }
    atoms.push_back(a);
  }
  return atoms;
}

}  // namespace demcal::test
