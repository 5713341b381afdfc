#pragma once
// Two fixed disks whose motion the test imposes, to check one contact law
// against its closed form.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem::testing {

// Two touching disks of radius r at (0, 0) and (2r, 0), both fixed (the test
// imposes their motion), joined by `model` with its bond installed; a fixed
// time step and no damping, so each step's forces follow the closed form.
inline World bonded_fixed_pair(const std::string& model, const nlohmann::json& parameters, double radius_m,
                               double dt_s) {
  WorldSettings settings;
  settings.fixed_dt_s = dt_s;
  settings.damping = 0;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(model, parameters, "test")));
  world.bodies.add_disk(0, 0, radius_m, 2650, 1, 0);
  world.bodies.add_disk(2 * radius_m, 0, radius_m, 2650, 1, 0);
  world.bodies.fixed[0] = world.bodies.fixed[1] = 1;
  EXPECT_EQ(world.install_bonds(1e-9, 1), 1u);
  return world;
}

// One step with disk 1 moving at (vx, vy) and the disks spinning at -w and +w
// (both disks are `fixed`, so the integrator leaves them where the test puts them).
inline void imposed_step(World& world, double vx, double vy, double w) {
  const double dt = world.settings().fixed_dt_s;
  world.bodies.vx[1] = vx;
  world.bodies.vy[1] = vy;
  world.bodies.w[0] = -w;
  world.bodies.w[1] = w;
  world.step();
  world.bodies.x[1] += vx * dt;
  world.bodies.y[1] += vy * dt;
}

}  // namespace demcal::dem::testing
