#pragma once
// A packed specimen as a LAMMPS data file (atom_style sphere, 2D), so the
// same disks can be run in LAMMPS: `make bench` compares the two engines on
// one specimen (scripts/bench_lammps.sh).
#include <string>

#include "demcal/dem/genesis.hpp"

namespace demcal::dem {

// Writes ids 1..N in the specimen's order, type 1, diameters, the density in
// kg/m^3, positions as the shortest text that reads back to the same doubles,
// and z = 0.
// The box is the specimen's, the z extent its thickness. LAMMPS's read_data
// takes a sphere's mass from the density; an input script for disks sets
// `set group all density/disc (density x thickness)` after reading, as the
// comment line of the file says.
void write_lammps_data(const Specimen& specimen, const std::string& path, const std::string& title);

}  // namespace demcal::dem
