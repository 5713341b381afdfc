#pragma once
// The disks' integration, one loop shared by the serial step (world.cpp) and
// the threaded one (world_threads.cpp), so both move the disks with the same
// arithmetic.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "demcal/dem/bodies.hpp"

namespace demcal::dem {

// What the disks' integration reads and writes.
struct DiskArrays {
  double *x, *y, *vx, *vy, *w;
  const double *force_x, *force_y, *moment, *mass, *inverse_mass, *inverse_inertia, *x_built, *y_built;
  const std::uint8_t* fixed;
  const std::int32_t* clump;
  const double* rolling_limit = nullptr;  // type A rolling resistance's couple per disk; nullptr: none
};

// A spin after one step of Coulomb friction in rotation: `trial` (the spin the
// other moments would give) shrunk towards zero by `slowing` (the rolling
// limit's couple times dt / I), and held at zero when the limit exceeds what
// would turn it: static rolling resistance.
inline double rolling_friction_spin(double trial, double slowing) {
  const double left = std::max(0.0, std::abs(trial) - slowing);
  return trial > 0 ? left : (trial < 0 ? -left : 0.0);
}

// Moves the free disks [from, to) one step; returns the largest squared
// move since the last rebuild among them and `max_move2`. With rolling limits
// the spin update takes rolling_friction_spin (a separate loop: without them
// the arithmetic, and so the bits, stay as they were).
template <bool kRollingLimits>
inline double integrate_disks_loop(const DiskArrays& a, std::size_t from, std::size_t to, double dt, double alpha,
                                   double gx, double gy, double max_move2) {
  // Local pointers, so they stay in registers through the loop.
  double* __restrict x = a.x;
  double* __restrict y = a.y;
  double* __restrict vx = a.vx;
  double* __restrict vy = a.vy;
  double* __restrict w = a.w;
  const double* __restrict force_x = a.force_x;
  const double* __restrict force_y = a.force_y;
  const double* __restrict moment = a.moment;
  const double* __restrict mass = a.mass;
  const double* __restrict inverse_mass = a.inverse_mass;
  const double* __restrict inverse_inertia = a.inverse_inertia;
  const double* __restrict x_built = a.x_built;
  const double* __restrict y_built = a.y_built;
  const std::uint8_t* __restrict fixed = a.fixed;
  const std::int32_t* __restrict clump = a.clump;
  const double* __restrict rolling_limit = a.rolling_limit;
  // No branch in the loop, so it vectorises: a fixed disk, and a clump's
  // member (which its clump moves afterwards), get `moves` = 0, which stops
  // them (v = 0, x unchanged) with the free disks' arithmetic untouched.
  // The max is exact in any order, so the vector lanes may take it apart.
#pragma omp simd reduction(max : max_move2)
  for (std::size_t i = from; i < to; ++i) {
    const double moves = (fixed[i] == 0) & (clump[i] < 0) ? 1.0 : 0.0;
    const double m = mass[i];
    // Local non-viscous damping opposes the velocity with a fraction of the
    // force.
    const double fx = force_x[i] + m * gx;
    const double fy = force_y[i] + m * gy;
    const double mz = moment[i];
    const double sx = vx[i] > 0 ? 1.0 : (vx[i] < 0 ? -1.0 : 0.0);
    const double sy = vy[i] > 0 ? 1.0 : (vy[i] < 0 ? -1.0 : 0.0);
    const double sw = w[i] > 0 ? 1.0 : (w[i] < 0 ? -1.0 : 0.0);
    const double to_velocity = inverse_mass[i] * dt;
    const double new_vx = (vx[i] + (fx - alpha * std::abs(fx) * sx) * to_velocity) * moves;
    const double new_vy = (vy[i] + (fy - alpha * std::abs(fy) * sy) * to_velocity) * moves;
    if constexpr (kRollingLimits) {
      const double trial = w[i] + (mz - alpha * std::abs(mz) * sw) * (inverse_inertia[i] * dt);
      w[i] = rolling_friction_spin(trial, rolling_limit[i] * (inverse_inertia[i] * dt)) * moves;
    } else {
      w[i] = (w[i] + (mz - alpha * std::abs(mz) * sw) * (inverse_inertia[i] * dt)) * moves;
    }
    vx[i] = new_vx;
    vy[i] = new_vy;
    x[i] += new_vx * dt;
    y[i] += new_vy * dt;
    const double ddx = x[i] - x_built[i], ddy = y[i] - y_built[i];
    max_move2 = std::max(max_move2, ddx * ddx + ddy * ddy);
  }
  return max_move2;
}

inline double integrate_disks(const DiskArrays& a, std::size_t from, std::size_t to, double dt, double alpha, double gx,
                              double gy, double max_move2) {
  return a.rolling_limit ? integrate_disks_loop<true>(a, from, to, dt, alpha, gx, gy, max_move2)
                         : integrate_disks_loop<false>(a, from, to, dt, alpha, gx, gy, max_move2);
}

inline DiskArrays disk_arrays(Bodies& b, const std::vector<double>& inverse_mass,
                              const std::vector<double>& inverse_inertia, const std::vector<double>& x_built,
                              const std::vector<double>& y_built) {
  return DiskArrays{b.x.data(),
                    b.y.data(),
                    b.vx.data(),
                    b.vy.data(),
                    b.w.data(),
                    b.fx.data(),
                    b.fy.data(),
                    b.moment.data(),
                    b.mass.data(),
                    inverse_mass.data(),
                    inverse_inertia.data(),
                    x_built.data(),
                    y_built.data(),
                    b.fixed.data(),
                    b.clump.data()};
}

}  // namespace demcal::dem
