#pragma once
// A packed 3D specimen for another engine: a LAMMPS data file (atom_style
// sphere) or a text file of "x y z r" lines, the format YADE's ymport.text
// reads. `make bench` runs LAMMPS and YADE on the same spheres as ours.
#include <string>

#include "demcal/dem3d/genesis.hpp"

namespace demcal::dem3d {

// Ids 1..N in the specimen's order, type 1, diameters, the density in
// kg/m^3 and positions as the shortest text that reads back to the same
// doubles (format_double); the
// box is the spheres' extent. Written atomically; an empty specimen is an Error.
void write_lammps_data(const SphereSpecimen& specimen, const std::string& path, const std::string& title);

// One sphere per line, "x y z r" in metres (the same doubles read back), after '#' lines
// that name the specimen and its density.
void write_sphere_text(const SphereSpecimen& specimen, const std::string& path, const std::string& title);

}  // namespace demcal::dem3d
