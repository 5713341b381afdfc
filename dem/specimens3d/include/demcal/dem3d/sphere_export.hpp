#pragma once
// A packed 3D specimen for another engine: a LAMMPS data file (atom_style
// sphere) or a text file of "x y z r" lines, the format YADE's ymport.text
// reads. `make bench` runs LAMMPS and YADE on the same spheres as ours.
#include <string>

#include "demcal/dem3d/genesis.hpp"

namespace demcal::dem3d {

// Ids 1..N in the specimen's order, type 1, diameters, the density in
// kg/m^3 and positions to 17 digits (the same doubles when read back); the
// box is the spheres' extent. Written atomically; an empty specimen is an Error.
void write_lammps_data(const SphereSpecimen& specimen, const std::string& path, const std::string& title);

// One sphere per line, "x y z r" in metres to 17 digits, after '#' lines
// that name the specimen and its density.
void write_sphere_text(const SphereSpecimen& specimen, const std::string& path, const std::string& title);

}  // namespace demcal::dem3d
