#pragma once
// Two fixed disks whose motion the test imposes, to check one contact law
// against its closed form.
#include "demcal/dem/world.hpp"

namespace demcal::dem::testing {

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
