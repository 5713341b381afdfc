// A sphere on a triangle mesh touches each facet it overlaps, but a point the
// facets share (an edge, a corner) must push once: a sphere on the ridge
// between two facets, or on one facet next to its edge, would otherwise feel
// the shared point twice (LIGGGHTS's mesh contacts face the same question).
// Rule: every face contact stays; an edge or vertex contact stays only when
// its closest point lies on no facet the sphere touches at the face and
// coincides with no edge or vertex contact kept before it (in pair order).
#include <cmath>

#include "demcal/dem3d/world.hpp"
#include "world_internals.hpp"

namespace demcal::dem3d {

void World::keep_one_contact_per_mesh_point() {
  Internals& in = *internals_;
  WallGeometryArrays& g = in.wall_geometry;
  const std::size_t count = wall_pairs_.size();
  // The wall pairs run by model, then sphere, then wall: a sphere's pairs with
  // one mesh are consecutive.
  std::size_t begin = 0;
  while (begin < count) {
    const std::int32_t sphere = wall_pairs_.i[begin];
    const std::int32_t mesh = walls[static_cast<std::size_t>(wall_pairs_.j[begin])].mesh;
    std::size_t end = begin + 1;
    while (end < count && wall_pairs_.i[end] == sphere && wall_pairs_.model[end] == wall_pairs_.model[begin] &&
           walls[static_cast<std::size_t>(wall_pairs_.j[end])].mesh == mesh)
      ++end;
    if (mesh >= 0 && end - begin > 1) {
      const auto i = static_cast<std::size_t>(sphere);
      const Vec3 centre = spheres.position(i);
      const double tolerance = 1e-9 * spheres.radius[i];
      auto closest = [&](std::size_t k) {
        return centre + (spheres.radius[i] - g.overlap[k]) * Vec3{g.nx[k], g.ny[k], g.nz[k]};
      };
      for (std::size_t k = begin; k < end; ++k) {
        if (!(g.overlap[k] > 0) || g.feature[k] == WallFeature::face) continue;
        const Vec3 point = closest(k);
        bool shared = false;
        for (std::size_t f = begin; f < end && !shared; ++f) {
          if (f == k || !(g.overlap[f] > 0)) continue;
          const Wall& other = walls[static_cast<std::size_t>(wall_pairs_.j[f])];
          if (g.feature[f] == WallFeature::face)
            shared = norm(closest_point_on_triangle(other, point) - point) <= tolerance;
          else if (f < k)
            shared = norm(closest(f) - point) <= tolerance;
        }
        if (shared) g.overlap[k] = -1e300;  // pushed by another facet's contact
      }
    }
    begin = end;
  }
}

}  // namespace demcal::dem3d
