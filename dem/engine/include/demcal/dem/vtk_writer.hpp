#pragma once
// Legacy-VTK snapshots for ParaView: disks as points (radius, velocity,
// clump id) with intact bonds as lines, bond breaks as points with their
// mode (0 tension, 1 shear) and time, and the walls (platens, vessel) as
// lines with their force and whether they act.
#include <string>

#include "demcal/dem/world.hpp"

namespace demcal::dem {

void write_vtk_disks(const World& world, const std::string& path);
void write_vtk_breaks(const World& world, const std::string& path);
void write_vtk_walls(const World& world, const std::string& path);

}  // namespace demcal::dem
