#include "demcal/dem3d/hertz_base.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem3d/linear_contact.hpp"

namespace demcal::dem3d {

double sphere_rolling_inertia_kg_m2(double mass_i_kg, double radius_i_m, double mass_j_kg, double radius_j_m) {
  const double a = mass_i_kg * radius_i_m * radius_i_m, b = mass_j_kg * radius_j_m * radius_j_m;
  if (a <= 0) return 1.4 * b;
  if (b <= 0) return 1.4 * a;
  return 1.4 * a * b / (a + b);
}

HertzBase::HertzBase(const nlohmann::json& p, const std::string& where) {
  const dem::HertzMaterial m = dem::HertzMaterial::read(p, where);
  e_eff_pa_ = m.e_eff_pa, g_eff_pa_ = m.g_eff_pa, friction_ = m.friction, overlap_ratio_ = m.overlap_ratio;
  // The 2D base's formula grouped as the 3D model always had it (one ulp
  // apart for some restitutions): its runs keep their bits.
  const double log_e = std::log(m.restitution);
  damping_ = -2.0 * std::sqrt(5.0 / 6.0) * log_e / std::sqrt(log_e * log_e + M_PI * M_PI);
  rolling_ = m.rolling;
}

std::vector<std::string> HertzBase::state_columns() const {
  return {"radius_eff_m",         "mass_eff_kg",          "shear_force_x_n",        "shear_force_y_n",
          "shear_force_z_n",      "max_contact_radius_m", "rolling_inertia_kg_m2",  "rolling_moment_x_nm",
          "rolling_moment_y_nm",  "rolling_moment_z_nm",  "contact_radius_m",
          "normal_velocity_m_s"};
}

void HertzBase::initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const {
  const double ri = pair.radius_i, rj = pair.radius_j;
  c.column[kRadiusEff][k] = pair.wall ? ri : ri * rj / (ri + rj);
  const double mi = pair.mass_i_kg, mj = pair.mass_j_kg;
  c.column[kMassEff][k] = mi > 0 && mj > 0 ? mi * mj / (mi + mj) : std::max(mi, mj);
  c.column[kRollingInertia][k] = sphere_rolling_inertia_kg_m2(mi, ri, mj, rj);
}

void HertzBase::release(PairBlock& c, std::size_t k, const PairForces& out) {
  for (std::size_t column :
       {kShearX, kShearY, kShearZ, kRollingX, kRollingY, kRollingZ, kContactRadius, kNormalVelocity})
    c.column[column][k] = 0;
  c.flags[k] &= ~static_cast<dem::PairFlags>(dem::kTouching);
  out.set(k, {}, {}, {});
}

void HertzBase::hertz_touch(PairBlock& c, std::size_t k, const PairForces& out, const PairContact& p, double dt,
                            const NormalForce& f, Vec3 spin_i, Vec3 spin_j) const {
  const Vec3 n = p.normal, relative_velocity = p.relative_velocity_m_s, plane_spin = p.plane_spin_rad_s;
  const double arm_i = p.arm_i_m, arm_j = p.arm_j_m;
  const double radius = c.column[kRadiusEff][k], mass = c.column[kMassEff][k];
  const double a = f.contact_radius_m;
  const double sn = 2.0 * e_eff_pa_ * a, st = 8.0 * g_eff_pa_ * a;
  c.column[kMaxContactRadius][k] = std::max(c.column[kMaxContactRadius][k], a);
  c.column[kContactRadius][k] = a;
  const double vn = dot(relative_velocity, n);  // < 0 approaching
  // The velocities are half a step behind the positions (leapfrog). A dashpot
  // fed them lags the overlap and returns too low a restitution at a strong
  // damping (e 0.1 came back 9 % low at 8 % of the Rayleigh step); the normal
  // one is fed the velocity at the step's own time, extrapolated from the last
  // two half steps (free flight before the touch: no change). Its stability
  // limit stays above the step max_damping_ratio() sets.
  const double vn_before = c.flags[k] & dem::kTouching ? c.column[kNormalVelocity][k] : vn;
  c.column[kNormalVelocity][k] = vn;
  const double vn_now = 1.5 * vn - 0.5 * vn_before;
  // The dashpot may pull at the end of an impact: clipping it would change e.
  const double normal = f.total_n - damping_ * std::sqrt(sn * mass) * vn_now;
  const Vec3 vt = relative_velocity - vn * n;
  // The stored shear spring, turned with the contact plane, incremented, capped.
  Vec3 spring = turned_shear({c.column[kShearX][k], c.column[kShearY][k], c.column[kShearZ][k]}, n, plane_spin, dt);
  spring = spring + (st * dt) * vt;
  const double limit = friction_ * std::max(0.0, f.repulsive_n), size = norm(spring);
  Vec3 shear;
  if (size >= limit) {
    spring = (size > 0 ? limit / size : 0.0) * spring;
    shear = spring;
  } else {
    shear = spring + (damping_ * std::sqrt(st * mass)) * vt;
  }
  c.column[kShearX][k] = spring.x, c.column[kShearY][k] = spring.y, c.column[kShearZ][k] = spring.z;
  c.flags[k] |= dem::kTouching;
  const Vec3 force = shear - normal * n;
  const Vec3 n_cross_fs = cross(n, shear);
  Vec3 moment_i = arm_i * n_cross_fs, moment_j = arm_j * n_cross_fs;
  if (rolling_.type == dem::RollingResistance::Type::Epsd || rolling_.type == dem::RollingResistance::Type::CdtRelative) {
    // The rolling part of j's spin relative to i's, and the couple on j.
    const Vec3 relative_spin = spin_j - spin_i;
    const Vec3 rolling = relative_spin - dot(relative_spin, n) * n;
    const double rolling_limit = rolling_.friction * radius * std::max(0.0, f.repulsive_n);
    Vec3 couple;
    if (rolling_.type == dem::RollingResistance::Type::CdtRelative) {
      couple = (-rolling_limit / std::max(norm(rolling), rolling_.threshold_rad_s)) * rolling;
    } else {
      const double kr = rolling_.spring_nm_rad(sn, radius);
      Vec3 elastic = turned_shear({c.column[kRollingX][k], c.column[kRollingY][k], c.column[kRollingZ][k]}, n,
                                  plane_spin, dt);
      elastic = elastic - (kr * dt) * rolling;
      const double elastic_size = norm(elastic);
      if (elastic_size >= rolling_limit) {  // fully mobilised: plastic, no dashpot
        elastic = (elastic_size > 0 ? rolling_limit / elastic_size : 0.0) * elastic;
        couple = elastic;
      } else {
        const double dashpot = rolling_.damping * 2.0 * std::sqrt(c.column[kRollingInertia][k] * kr);
        couple = elastic - dashpot * rolling;
      }
      c.column[kRollingX][k] = elastic.x, c.column[kRollingY][k] = elastic.y, c.column[kRollingZ][k] = elastic.z;
    }
    moment_i = moment_i - couple;
    moment_j = moment_j + couple;
  }
  out.set(k, force, moment_i, moment_j);
}

void HertzBase::stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                          double& rotational_nm_rad) const {
  const double radius = c.column[kRadiusEff][k];
  const double a = std::max(c.column[kMaxContactRadius][k], radius * std::sqrt(overlap_ratio_));
  const double sn = 2.0 * e_eff_pa_ * a, st = 8.0 * g_eff_pa_ * a;
  translational_n_m = std::max(sn, st);
  rotational_nm_rad = st * arm_m * arm_m + rolling_.spring_nm_rad(sn, radius);
}

double HertzBase::stiffness_estimate(double radius_m) const {
  const double a = 0.5 * radius_m * std::sqrt(overlap_ratio_);  // two equal spheres: R* = r / 2
  return std::max(2.0 * e_eff_pa_ * a, 8.0 * g_eff_pa_ * a);
}

double HertzBase::max_damping_ratio() const {
  const double tangential = std::sqrt(3.5) * 0.5 * damping_;
  return std::max(tangential, rolling_.type == dem::RollingResistance::Type::Epsd ? rolling_.damping : 0.0);
}

void HertzBase::add_rolling_limits(const ConstPairBlock& c, const Spheres& s, bool walls, double* limit_nm) const {
  if (rolling_.type != dem::RollingResistance::Type::Cdt) return;
  for (std::size_t k = 0; k < c.size; ++k) {
    if (!(c.flags[k] & dem::kTouching)) continue;
    const double a = c.column[kContactRadius][k];
    const double repulsive = 4.0 / 3.0 * e_eff_pa_ * a * a * a / c.column[kRadiusEff][k];
    const auto i = static_cast<std::size_t>(c.i[k]);
    limit_nm[i] += rolling_.friction * s.radius[i] * repulsive;
    if (!walls) {
      const auto j = static_cast<std::size_t>(c.j[k]);
      limit_nm[j] += rolling_.friction * s.radius[j] * repulsive;
    }
  }
}

}  // namespace demcal::dem3d
