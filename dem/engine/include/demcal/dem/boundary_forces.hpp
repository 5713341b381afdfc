#pragma once
// What stands in for a removed wall (Ma et al. 2022, after Lysmer and
// Kuhlemeyer 1969): each disk the wall touched keeps the static force the
// wall gave it (F_app, so the model stays at rest), and a viscous boundary
// adds dashpots against its velocity, normal and tangential to the side:
//   F_n = F_app,n - c_n v_n,  c_n = 2 R t xi  rho C_P
//   F_s = F_app,s - c_s v_s,  c_s = 2 R t eta rho C_S
// An input boundary carries an incoming wave as well: the dashpot acts on
// v - 2 v_wave (half of the applied traction feeds the dashpot; the other
// half makes the wave), P along the inward normal, S along the tangent.
// A free boundary is one with no dashpots (it keeps F_app only); a fixed
// one is made by fixing its disks, not here. A velocity input is a fixed
// side whose disks move with the incoming wave's particle velocity and stand
// still once it has passed (Ma et al.'s fixed boundary with the pulse imposed):
// it reflects whatever comes back to it, as a fixed side does.
//
// It counts the work it does on the model, so a test can close its energy
// balance: the input's, the dashpots' (<= 0: what they absorb) and the
// static forces'.
#include <cstddef>
#include <functional>
#include <vector>

#include "demcal/dem/external_forces.hpp"

namespace demcal::dem {

struct BoundaryDisk {
  std::size_t disk = 0;
  double outward_nx = 0, outward_ny = 0;  // unit normal of the side, out of the model
  double applied_fx_n = 0, applied_fy_n = 0, applied_moment_nm = 0;  // F_app and the wall's moment
  double normal_dashpot_n_s_m = 0;  // c_n; 0: none
  double shear_dashpot_n_s_m = 0;   // c_s; 0: none
  bool input = false;               // carries the incoming wave
  bool prescribed = false;          // a fixed disk moved with the wave's velocity (a velocity input)
};

class BoundaryForces : public ExternalForces {
 public:
  // Particle velocity of the incoming P and S waves at time t, m/s (along
  // the inward normal and the tangent obtained by turning it 90 degrees
  // anticlockwise).
  using Wave = std::function<double(double time_s)>;

  void add_disk(const BoundaryDisk& disk) { disks_.push_back(disk); }
  void set_input(Wave p_wave_m_s, Wave s_wave_m_s);
  const std::vector<BoundaryDisk>& disks() const { return disks_; }

  void add(Bodies& bodies, double time_s, double dt_s) override;
  void after_integration(Bodies& bodies, double time_s, double dt_s) override;

  double input_work_j() const { return input_work_j_; }
  double dashpot_work_j() const { return dashpot_work_j_; }  // <= 0
  double applied_work_j() const { return applied_work_j_; }
  // Sets the three work sums (a run resumed from a checkpoint carries on from them).
  void restore_work(double input_j, double dashpot_j, double applied_j) {
    input_work_j_ = input_j;
    dashpot_work_j_ = dashpot_j;
    applied_work_j_ = applied_j;
  }

 private:
  std::vector<BoundaryDisk> disks_;
  Wave p_wave_, s_wave_;
  double input_work_j_ = 0, dashpot_work_j_ = 0, applied_work_j_ = 0;
};

}  // namespace demcal::dem
