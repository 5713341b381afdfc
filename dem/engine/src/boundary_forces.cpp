#include "demcal/dem/boundary_forces.hpp"

#include <utility>

namespace demcal::dem {

void BoundaryForces::set_input(Wave p_wave_m_s, Wave s_wave_m_s) {
  p_wave_ = std::move(p_wave_m_s);
  s_wave_ = std::move(s_wave_m_s);
}

void BoundaryForces::add(Bodies& bodies, double time_s, double dt_s) {
  const double p = p_wave_ ? p_wave_(time_s) : 0.0, s = s_wave_ ? s_wave_(time_s) : 0.0;
  for (const BoundaryDisk& d : disks_) {
    const std::size_t i = d.disk;
    // Inward normal and the tangent 90 degrees anticlockwise from it.
    const double nx = -d.outward_nx, ny = -d.outward_ny, tx = -ny, ty = nx;
    const double vn = bodies.vx[i] * nx + bodies.vy[i] * ny, vs = bodies.vx[i] * tx + bodies.vy[i] * ty;
    double fn = -d.normal_dashpot_n_s_m * vn, fs = -d.shear_dashpot_n_s_m * vs;
    dashpot_work_j_ += (fn * vn + fs * vs) * dt_s;
    if (d.input) {
      const double in_n = 2 * d.normal_dashpot_n_s_m * p, in_s = 2 * d.shear_dashpot_n_s_m * s;
      fn += in_n;
      fs += in_s;
      input_work_j_ += (in_n * vn + in_s * vs) * dt_s;
    }
    bodies.fx[i] += d.applied_fx_n + fn * nx + fs * tx;
    bodies.fy[i] += d.applied_fy_n + fn * ny + fs * ty;
    bodies.moment[i] += d.applied_moment_nm;
    applied_work_j_ += (d.applied_fx_n * bodies.vx[i] + d.applied_fy_n * bodies.vy[i]) * dt_s;
  }
}

void BoundaryForces::after_integration(Bodies& bodies, double time_s, double dt_s) {
  // The integration's velocities belong to the half step: so do the prescribed ones.
  const double mid = time_s + 0.5 * dt_s;
  const double p = p_wave_ ? p_wave_(mid) : 0.0, s = s_wave_ ? s_wave_(mid) : 0.0;
  for (const BoundaryDisk& d : disks_) {
    if (!d.prescribed) continue;
    const std::size_t i = d.disk;
    const double nx = -d.outward_nx, ny = -d.outward_ny, tx = -ny, ty = nx;
    const double vx = p * nx + s * tx, vy = p * ny + s * ty;
    // The work the side does on the rest of the model: against the force the model puts on the disk (its
    // contacts'; F_app is counted as the other disks' is).
    input_work_j_ -= ((bodies.fx[i] - d.applied_fx_n) * vx + (bodies.fy[i] - d.applied_fy_n) * vy) * dt_s;
    bodies.vx[i] = vx;
    bodies.vy[i] = vy;
    bodies.w[i] = 0;
    bodies.x[i] += vx * dt_s;
    bodies.y[i] += vy * dt_s;
  }
}

}  // namespace demcal::dem
