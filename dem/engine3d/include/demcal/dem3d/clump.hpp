#pragma once
// A rigid clump of spheres (a multi-sphere particle): its mass, its principal
// moments of inertia with the orientation of its principal axes (a unit
// quaternion, body to world), its centre of mass, velocity and angular
// momentum, and its member spheres by id with their places in the body frame.
// The world moves the members with it; contacts between members are dropped.
#include <cstdint>
#include <vector>

#include "demcal/dem3d/vec3.hpp"
#include "demcal/dem3d/quaternion.hpp"

namespace demcal::dem3d {

struct Clump {
  double mass_kg = 0;
  Vec3 principal_inertia_kg_m2;  // about the principal axes through the centre of mass
  Quaternion orientation;        // principal (body) axes to world
  Vec3 centre_m;
  Vec3 velocity_m_s;
  Vec3 angular_momentum;  // about the centre, world frame, kg m^2/s
  std::vector<std::uint32_t> member_ids;
  std::vector<Vec3> member_offsets_body_m;  // member centre - clump centre, in the body frame

  // The angular velocity the angular momentum gives at `q`: R I^-1 R^T L.
  Vec3 spin_at(Quaternion q) const {
    const Vec3 l = to_body(q, angular_momentum);
    return to_world(q, {l.x / principal_inertia_kg_m2.x, l.y / principal_inertia_kg_m2.y,
                        l.z / principal_inertia_kg_m2.z});
  }
  Vec3 spin() const { return spin_at(orientation); }
  // Translational and rotational kinetic energy, J.
  double kinetic_energy() const { return 0.5 * mass_kg * dot(velocity_m_s, velocity_m_s) + 0.5 * dot(spin(), angular_momentum); }
};

// What a clump of given spheres weighs and how it turns: mass, centre of mass,
// principal moments and the orientation of the principal axes, summing the
// spheres as solids of `density_kg_m3` (where spheres overlap, the shared
// volume counts once per sphere, as PFC's clump templates count pebbles; a
// shape's exact mass and inertia, when known, can be passed to add_clump
// instead).
struct ClumpShape {
  double mass_kg = 0;
  Vec3 centre_m;
  Vec3 principal_inertia_kg_m2;
  Quaternion orientation;
};
ClumpShape clump_of_spheres(const std::vector<Vec3>& centres_m, const std::vector<double>& radii_m,
                            double density_kg_m3);

}  // namespace demcal::dem3d
