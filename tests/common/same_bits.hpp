#pragma once
// Two runs of one scene hold the same bits: every disk's position, velocity,
// spin and sums, the walls' forces, the break log, the rebuilds and the time
// step. For runs that must not depend on how they were spread over threads.
#include <gtest/gtest.h>

#include "demcal/dem/world.hpp"

namespace demcal::test {

inline void expect_same_bits(const dem::World& a, const dem::World& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    ASSERT_EQ(a.bodies.x[k], b.bodies.x[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.y[k], b.bodies.y[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.vx[k], b.bodies.vx[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.vy[k], b.bodies.vy[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.w[k], b.bodies.w[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.fx[k], b.bodies.fx[k]) << "disk " << k;
    ASSERT_EQ(a.bodies.moment[k], b.bodies.moment[k]) << "disk " << k;
  }
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t w = 0; w < a.walls.size(); ++w) EXPECT_EQ(a.walls[w].fy, b.walls[w].fy) << "wall " << w;
  ASSERT_EQ(a.breaks().size(), b.breaks().size());
  for (std::size_t e = 0; e < a.breaks().size(); ++e) {
    EXPECT_EQ(a.breaks()[e].time_s, b.breaks()[e].time_s) << "break " << e;
    EXPECT_EQ(a.breaks()[e].x_m, b.breaks()[e].x_m) << "break " << e;
    EXPECT_EQ(a.breaks()[e].mode, b.breaks()[e].mode) << "break " << e;
  }
  EXPECT_EQ(a.rebuilds(), b.rebuilds());
  EXPECT_EQ(a.dt_s(), b.dt_s());
}

// The same for two runs whose disks are stored in different orders: each
// disk compared with the one of the same id (position, velocity, spin), and
// the walls' forces, the breaks and the time step.
inline void expect_same_bits_per_id(const dem::World& a, const dem::World& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  std::vector<std::size_t> index_b(b.bodies.size());
  for (std::size_t k = 0; k < b.bodies.size(); ++k) index_b[b.bodies.id[k]] = k;
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    const std::size_t m = index_b[a.bodies.id[k]];
    ASSERT_EQ(a.bodies.x[k], b.bodies.x[m]) << "disk " << a.bodies.id[k];
    ASSERT_EQ(a.bodies.y[k], b.bodies.y[m]) << "disk " << a.bodies.id[k];
    ASSERT_EQ(a.bodies.vx[k], b.bodies.vx[m]) << "disk " << a.bodies.id[k];
    ASSERT_EQ(a.bodies.vy[k], b.bodies.vy[m]) << "disk " << a.bodies.id[k];
    ASSERT_EQ(a.bodies.w[k], b.bodies.w[m]) << "disk " << a.bodies.id[k];
  }
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t w = 0; w < a.walls.size(); ++w) EXPECT_EQ(a.walls[w].fy, b.walls[w].fy) << "wall " << w;
  EXPECT_EQ(a.breaks().size(), b.breaks().size());
  EXPECT_EQ(a.dt_s(), b.dt_s());
}

}  // namespace demcal::test
