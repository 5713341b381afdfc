#include "demcal/dem/hertz_base.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>


namespace demcal::dem {

double restitution_beta(double restitution) {
  const double log_e = std::log(restitution);
  return log_e / std::sqrt(log_e * log_e + M_PI * M_PI);
}

HertzBase::HertzBase(const nlohmann::json& p, const std::string& where) {
  const HertzMaterial m = HertzMaterial::read(p, where);
  e_eff_pa_ = m.e_eff_pa, g_eff_pa_ = m.g_eff_pa, friction_ = m.friction, overlap_ratio_ = m.overlap_ratio;
  damping_ = -2.0 * std::sqrt(5.0 / 6.0) * restitution_beta(m.restitution);
  rolling_ = m.rolling;
}

std::vector<std::string> HertzBase::state_columns() const {
  return {"radius_eff_m",     "mass_eff_kg",      "rolling_inertia_kg_m2", "shear_force_n",
          "rolling_moment_nm", "contact_radius_m", "max_contact_radius_m", "normal_velocity_m_s"};
}

void HertzBase::initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double) const {
  const double ri = pair.radius_i, rj = pair.radius_j;
  c.column[kRadiusEff][k] = pair.wall ? ri : ri * rj / (ri + rj);
  const double mi = pair.mass_i_kg, mj = pair.mass_j_kg;
  c.column[kMassEff][k] = mi > 0 && mj > 0 ? mi * mj / (mi + mj) : std::max(mi, mj);
  c.column[kRollingInertia][k] = rolling_inertia_kg_m2(mi, ri, mj, rj);
  c.column[kHertzShearForce][k] = 0;
  c.column[kRollingMoment][k] = 0;
  c.column[kContactRadius][k] = 0;
  c.column[kMaxContactRadius][k] = 0;
  c.column[kNormalVelocity][k] = 0;
}

void HertzBase::release(const PairBlock& c, std::size_t k) {
  c.column[kHertzShearForce][k] = 0;
  c.column[kRollingMoment][k] = 0;
  c.column[kContactRadius][k] = 0;
  c.column[kNormalVelocity][k] = 0;
  c.flags[k] &= ~static_cast<PairFlags>(kTouching);
}

PairForce HertzBase::hertz_force(const PairBlock& c, std::size_t k, const Geometry& g, double dt_s,
                                 const NormalForce& n) const {
  PairForce f;
  const double a = n.contact_radius_m;
  const double mass = c.column[kMassEff][k];
  const double sn = 2.0 * e_eff_pa_ * a, st = 8.0 * g_eff_pa_ * a;
  // The velocities are half a step behind the positions (leapfrog). A dashpot
  // fed them lags the overlap and returns too low a restitution at a strong
  // damping; the normal one is fed the velocity at the step's own time,
  // extrapolated from the last two half steps (free flight before the touch:
  // no change). As the 3D model (dem/models3d/src/hertz_base.cpp).
  const double vn_before = c.flags[k] & kTouching ? c.column[kNormalVelocity][k] : g.vn;
  c.column[kNormalVelocity][k] = g.vn;
  c.flags[k] |= kTouching;
  c.column[kContactRadius][k] = a;
  c.column[kMaxContactRadius][k] = std::max(c.column[kMaxContactRadius][k], a);
  // The dashpot may pull at the end of an impact: clipping it would change e.
  f.fn = n.total_n - damping_ * std::sqrt(sn * mass) * (1.5 * g.vn - 0.5 * vn_before);
  double spring = c.column[kHertzShearForce][k] - st * g.vs * dt_s;
  const double limit = friction_ * std::max(0.0, n.repulsive_n);
  if (std::abs(spring) >= limit) {
    spring = std::copysign(limit, spring);
    f.fs = spring;
  } else {
    f.fs = spring - damping_ * std::sqrt(st * mass) * g.vs;
  }
  c.column[kHertzShearForce][k] = spring;
  f.moment = rolling_.moment(c.column[kRollingMoment][k], g.relative_w, dt_s, sn, n.repulsive_n,
                             c.column[kRadiusEff][k], c.column[kRollingInertia][k]);
  return f;
}

void HertzBase::stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                          double& rotational_nm_rad) const {
  const double radius = c.column[kRadiusEff][k];
  const double a = std::max(c.column[kMaxContactRadius][k], radius * std::sqrt(overlap_ratio_));
  const double sn = 2.0 * e_eff_pa_ * a, st = 8.0 * g_eff_pa_ * a;
  translational_n_m = std::max(sn, st);
  rotational_nm_rad = st * arm_m * arm_m + rolling_.spring_nm_rad(sn, radius);
}

void HertzBase::add_rolling_limits(const ConstPairBlock& c, const Bodies& b, bool walls, double* limit_nm) const {
  if (rolling_.type != RollingResistance::Type::Cdt) return;
  for (std::size_t k = 0; k < c.size; ++k) {
    if (!(c.flags[k] & kTouching)) continue;
    const double a = c.column[kContactRadius][k];
    const double repulsive = 4.0 / 3.0 * e_eff_pa_ * a * a * a / c.column[kRadiusEff][k];
    const std::size_t i = static_cast<std::size_t>(c.i[k]);
    limit_nm[i] += rolling_.friction * b.radius[i] * repulsive;
    if (!walls) {
      const std::size_t j = static_cast<std::size_t>(c.j[k]);
      limit_nm[j] += rolling_.friction * b.radius[j] * repulsive;
    }
  }
}

double HertzBase::max_damping_ratio() const {
  const double tangential = std::sqrt(3.0) * 0.5 * damping_;  // damping_ = 2 sqrt(5/6) |beta|
  return std::max(tangential, rolling_.type == RollingResistance::Type::Epsd ? rolling_.damping : 0.0);
}

double HertzBase::normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const {
  if (overlap_m <= 0) return 0.0;
  const double radius = c.column[kRadiusEff][k];
  return 4.0 / 3.0 * e_eff_pa_ * std::sqrt(radius) * overlap_m * std::sqrt(overlap_m);
}

double HertzBase::stiffness_estimate(double radius_m, double) const {
  const double a = 0.5 * radius_m * std::sqrt(overlap_ratio_);  // two equal disks: R* = r / 2
  return std::max(2.0 * e_eff_pa_ * a, 8.0 * g_eff_pa_ * a);
}

}  // namespace demcal::dem
