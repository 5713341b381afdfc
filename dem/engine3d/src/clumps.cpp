// The 3D world's rigid clumps: adding one, and moving each with its members'
// forces. Translation as a sphere's (local damping per component); rotation by
// the angular momentum L (so a free clump keeps L exactly), the orientation
// advanced by the spin at the half step (second order: a torque-free clump
// precesses as Euler's equations say).
#include <algorithm>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/world.hpp"
#include "world_internals.hpp"

namespace demcal::dem3d {

std::size_t World::add_clump(const std::vector<std::size_t>& members, double mass_kg, Vec3 principal_inertia_kg_m2,
                             Quaternion orientation, Vec3 centre_m) {
  if (members.empty()) throw Error("a clump needs at least one member sphere");
  if (!(mass_kg > 0) || !(principal_inertia_kg_m2.x > 0) || !(principal_inertia_kg_m2.y > 0) ||
      !(principal_inertia_kg_m2.z > 0))
    throw Error("a clump needs a positive mass and positive principal moments of inertia");
  const auto index = static_cast<std::int32_t>(clumps_.size());
  Clump c;
  c.mass_kg = mass_kg;
  c.principal_inertia_kg_m2 = principal_inertia_kg_m2;
  c.orientation = normalised(orientation);
  c.centre_m = centre_m;
  for (std::size_t i : members) {
    if (i >= spheres.size()) throw Error("a clump member is not a sphere of the world");
    if (spheres.fixed[i]) throw Error("a fixed sphere cannot join a clump");
    if (spheres.clump[i] >= 0) throw Error("sphere " + std::to_string(spheres.id[i]) + " is already in a clump (or given twice)");
    spheres.clump[i] = index;
    c.member_ids.push_back(spheres.id[i]);
    c.member_offsets_body_m.push_back(to_body(c.orientation, spheres.position(i) - centre_m));
  }
  clumps_.push_back(std::move(c));
  built_ = false;
  return static_cast<std::size_t>(index);
}

void World::integrate_clumps(double& max_move2) {
  Internals& in = *internals_;
  const double dt = dt_s_, alpha = settings_.damping;
  auto damped = [alpha](double rate, double load) {
    return load - alpha * std::abs(load) * (rate > 0 ? 1.0 : (rate < 0 ? -1.0 : 0.0));
  };
  // Each clump writes only its own members, so the clumps split over threads as they come; the largest move is
  // a maximum, the same in any order: the bits do not depend on the thread count.
  const auto count = static_cast<std::ptrdiff_t>(clumps_.size());
  const int team = threads_in_use_;
#pragma omp parallel for num_threads(team) if (team > 1 && count > 256) schedule(static) reduction(max : max_move2)
  for (std::ptrdiff_t kk = 0; kk < count; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    Clump& c = clumps_[k];
    // The members' forces and moments about the centre, in member order.
    Vec3 force = c.mass_kg * settings_.gravity_m_s2, moment;
    std::vector<std::size_t>& index = in.member_index[k];
    for (std::size_t m = 0; m < index.size(); ++m) {
      const std::size_t i = index[m];
      const Vec3 f = {in.member_fx[i], in.member_fy[i], in.member_fz[i]};
      force = force + f;
      moment = moment + Vec3{in.member_mx[i], in.member_my[i], in.member_mz[i]} + cross(spheres.position(i) - c.centre_m, f);
    }
    in.clump_force[k] = force;
    const Vec3 spin = c.spin();
    const Vec3 f_d = {damped(c.velocity_m_s.x, force.x), damped(c.velocity_m_s.y, force.y), damped(c.velocity_m_s.z, force.z)};
    const Vec3 m_d = {damped(spin.x, moment.x), damped(spin.y, moment.y), damped(spin.z, moment.z)};
    c.velocity_m_s = c.velocity_m_s + (dt / c.mass_kg) * f_d;
    c.centre_m = c.centre_m + dt * c.velocity_m_s;
    c.angular_momentum = c.angular_momentum + dt * m_d;
    if (!in.rolling_limit.empty()) {
      // Type A rolling resistance: the members' couple limits, as Coulomb
      // friction in rotation against the clump's own spin; held still while
      // they exceed what would turn it.
      double limit = 0;
      for (std::size_t i : index) limit += in.rolling_limit[i];
      const Vec3 trial = c.spin();
      const double size = norm(trial);
      if (limit > 0 && size > 0) {
        const Vec3 direction = (1.0 / size) * trial;
        const double slowing = limit * dt;
        c.angular_momentum = dot(c.angular_momentum, direction) > slowing
                                 ? c.angular_momentum - slowing * direction
                                 : Vec3{};
      }
    }
    const Quaternion half = normalised(rotation_by((0.5 * dt) * c.spin_at(c.orientation)) * c.orientation);
    c.orientation = normalised(rotation_by(dt * c.spin_at(half)) * c.orientation);
    const Vec3 new_spin = c.spin();
    for (std::size_t m = 0; m < index.size(); ++m) {
      const std::size_t i = index[m];
      const Vec3 arm = to_world(c.orientation, c.member_offsets_body_m[m]);
      const Vec3 p = c.centre_m + arm;
      spheres.x[i] = p.x, spheres.y[i] = p.y, spheres.z[i] = p.z;
      spheres.set_velocity(i, c.velocity_m_s + cross(new_spin, arm));
      spheres.set_spin(i, new_spin);
      const double dx = p.x - in.x_built[i], dy = p.y - in.y_built[i], dz = p.z - in.z_built[i];
      max_move2 = std::max(max_move2, dx * dx + dy * dy + dz * dz);
    }
  }
}

}  // namespace demcal::dem3d
