#pragma once
// Triangle meshes from STL files (ASCII or binary, told apart by the file's
// size, since a binary file may begin with "solid" too), as walls of the 3D
// engine: each facet one WallShape::triangle of the same mesh, moving and
// spinning together about the mesh's pivot (set_mesh_motion).
#include <cstdint>
#include <string>
#include <vector>

#include "demcal/dem3d/walls.hpp"

namespace demcal::dem3d {

struct StlMesh {
  std::vector<Wall> triangles;
  bool closed = false;  // every edge shared by exactly two facets (a vessel that holds its contents)
  std::size_t facets_without_area = 0;  // left out (their corners in a line), with a warning
};

// Reads `path` as mesh number `mesh` of group `group`, scaled by `scale` (an
// STL has no units: 0.001 reads millimetres as metres) and shifted by
// `offset_m`; the pivot is the mesh's centroid. An Error naming the file and
// the facet for a file that is neither STL form or holds a coordinate that is
// not finite; with `must_be_closed`, for an open mesh too. Facets without area
// are left out with a warning (their edges still count for closedness).
StlMesh read_stl(const std::string& path, std::int32_t mesh, std::uint8_t group = 1, double scale = 1.0,
                 Vec3 offset_m = {}, bool must_be_closed = false);

// Every triangle of mesh `mesh` in `walls` moves at `velocity_m_s` and spins at
// `spin_rad_s` about `pivot_m`.
void set_mesh_motion(std::vector<Wall>& walls, std::int32_t mesh, Vec3 velocity_m_s, Vec3 spin_rad_s, Vec3 pivot_m);

// The sum of the forces on mesh `mesh`'s triangles (each triangle's moment_nm is about the pivot).
Vec3 mesh_force_n(const std::vector<Wall>& walls, std::int32_t mesh);

}  // namespace demcal::dem3d
