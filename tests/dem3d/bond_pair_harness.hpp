#pragma once
// One bonded pair (spheres 0 and 1) handed to a 3D contact model directly,
// so a test sets the spheres' motion itself and reads the force on 0 and
// the moments: the bonds' closed-form tests share it.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/core/rng.hpp"
#include "demcal/dem3d/contact_model.hpp"

namespace demcal::dem3d::bond_test {

constexpr double kRadius = 1e-3, kDensity = 2650;

struct Harness {
  std::unique_ptr<ContactModel> model;
  dem::ContactSet set;
  Spheres s;
  std::vector<double> f = std::vector<double>(9);
  double dt = 1e-8;

  Harness(const std::string& name, const nlohmann::json& p, Vec3 x0, Vec3 x1) {
    model = ContactModelRegistry::instance().create(name, p, "test");
    set.set_layout({model->state_columns().size()});
    set.assign_blocks({1});
    set.i[0] = 0, set.j[0] = 1;
    s.add_sphere(x0, kRadius, kDensity, 0);
    s.add_sphere(x1, kRadius, kDensity, 0);
    dem::PairBlock b = block();
    PairInfo info;
    info.radius_i = info.radius_j = kRadius;
    model->initialise(b, 0, info);
    const Vec3 d = x1 - x0;
    info.overlap_m = 2 * kRadius - norm(d);
    if (info.overlap_m > 0) model->make_force_free(b, 0, info.overlap_m);
    Rng rng(1, 2);
    EXPECT_TRUE(model->install_bond(b, 0, info, rng));
  }
  dem::PairBlock block() { return set.block(0); }
  PairForces out() { return {&f[0], &f[1], &f[2], &f[3], &f[5], &f[7]}; }
  void step() {
    dem::PairBlock b = block();
    model->sphere_forces(b, s, out(), {dt, 0});
  }
  // Moves sphere 1 with velocity v and both spins for `steps` steps.
  void move(int steps, Vec3 v1, Vec3 w0 = {}, Vec3 w1 = {}) {
    s.set_velocity(1, v1), s.set_spin(0, w0), s.set_spin(1, w1);
    for (int k = 0; k < steps; ++k) {
      step();
      s.x[1] += v1.x * dt, s.y[1] += v1.y * dt, s.z[1] += v1.z * dt;
    }
    s.set_velocity(1, {}), s.set_spin(0, {}), s.set_spin(1, {});
  }
  bool bonded() { return (set.flags[0] & dem::kBonded) != 0; }
  bool broke_in_tension() { return tension_breaks(set.flags[0]) > 0; }
  Vec3 force() const { return {f[0], f[1], f[2]}; }
  Vec3 moment_i() const { return {f[3], f[5], f[7]}; }
  Vec3 moment_j() const { return {f[4], f[6], f[8]}; }
};

// v turned by angle a about the unit axis u (Rodrigues).
inline Vec3 rotate(Vec3 v, Vec3 u, double a) {
  return std::cos(a) * v + std::sin(a) * cross(u, v) + ((1 - std::cos(a)) * dot(u, v)) * u;
}

}  // namespace demcal::dem3d::bond_test
