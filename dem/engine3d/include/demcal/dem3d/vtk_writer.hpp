#pragma once
// Legacy-VTK snapshots of a 3D world for ParaView: spheres as points (radius,
// id, velocity, spin; show them with a Glyph filter scaled by radius), intact
// bonds as lines, and the walls as surfaces (a plane as a square patch as wide
// as the spheres' extent, a cylinder as 32 facets) with their force.
#include <string>

#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {

void write_vtk_spheres(const World& world, const std::string& path);
void write_vtk_walls(const World& world, const std::string& path);

}  // namespace demcal::dem3d
