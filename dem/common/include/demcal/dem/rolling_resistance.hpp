#pragma once
// Rolling resistance: a couple that opposes the rotation of bodies in
// contact, the usual stand-in for the non-round shape of real grains (Ai,
// Chen, Rotter & Ooi 2011, Powder Technol. 206:269-282, whose type names are
// kept here).
//   type C, elastic-plastic spring-dashpot (LIGGGHTS "epsd"): the couple grows
//     by -k_r dtheta with k_r = 2.25 k_n mu_r^2 R*^2 up to mu_r R* F_n; while it
//     is below that limit a dashpot -C_r w_rel acts too, C_r = eta_r 2 sqrt(I_r k_r),
//     I_r = 1.5 (m_i R_i^2)(m_j R_j^2) / (m_i R_i^2 + m_j R_j^2) for disks
//     (1.5 m R^2 against a wall), the disks' inertia about their contact points.
//   type A, constant directional torque on each particle's own spin (EDEM's
//     standard rolling friction): each contact can give each of its bodies a
//     couple of up to mu_r R_i F_n against that body's rotation. The engine
//     applies the contacts' sum as Coulomb friction in rotation: it slows the
//     spin by at most that couple in a step and holds a body still while the
//     other moments on it stay below it (static resistance), so a body at rest
//     stays at rest instead of flipping its couple every step
//     (ContactModel::add_rolling_limits, World).
//   type A relative (LIGGGHTS "cdt"): -mu_r R* F_n against the sign of w_rel,
//     falling linearly to zero below a threshold angular velocity (w_rel /
//     threshold); no resistance at rest, kept for comparison with LIGGGHTS.
// F_n is the repulsive part of the normal force, k_n the normal contact
// stiffness now. In 2D w_rel = w_j - w_i; the couple acts on j, its opposite on i.
//   parameters (in the contact model's): "rolling_friction_epsd" (mu_r) with
//   "rolling_damping_epsd" (eta_r, default 0.3, Ai et al.'s choice), or
//   "rolling_friction_cdt" (mu_r, type A), or "rolling_friction_cdt_relative"
//   (mu_r) with "rolling_threshold_cdt_rad_s" (default 0.1).
#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace demcal::dem {

struct RollingResistance {
  enum class Type { None, Epsd, Cdt, CdtRelative };
  Type type = Type::None;
  double friction = 0;           // mu_r
  double damping = 0;            // eta_r (epsd)
  double threshold_rad_s = 0;    // below it the relative cdt couple falls linearly to zero

  // Reads the parameters above (none given: no rolling resistance); refuses
  // both types at once or a cdt threshold <= 0.
  static RollingResistance read(const nlohmann::json& p, const std::string& where);
  // The parameter names it reads, for a model's list of known parameters.
  static const char* const kParameters[5];

  // Rolling spring stiffness for normal stiffness `kn_n_m` (epsd), N m/rad.
  double spring_nm_rad(double kn_n_m, double radius_eff_m) const {
    return type == Type::Epsd ? 2.25 * kn_n_m * friction * friction * radius_eff_m * radius_eff_m : 0.0;
  }

  // The couple on j this step, N m. `spring_moment_nm` is the pair's stored
  // elastic couple (epsd), updated here; `rolling_inertia_kg_m2` its I_r.
  double moment(double& spring_moment_nm, double relative_w_rad_s, double dt_s, double kn_n_m,
                double repulsive_force_n, double radius_eff_m, double rolling_inertia_kg_m2) const {
    const double limit = friction * radius_eff_m * std::max(0.0, repulsive_force_n);
    if (type == Type::CdtRelative) return -limit * std::clamp(relative_w_rad_s / threshold_rad_s, -1.0, 1.0);
    if (type == Type::None || type == Type::Cdt) return 0.0;  // type A acts through the bodies' rolling limits
    const double kr = spring_nm_rad(kn_n_m, radius_eff_m);
    double spring = spring_moment_nm - kr * relative_w_rad_s * dt_s;
    if (std::abs(spring) >= limit) {  // fully mobilised: plastic, no dashpot
      spring_moment_nm = std::copysign(limit, spring);
      return spring_moment_nm;
    }
    spring_moment_nm = spring;
    return spring - damping * 2.0 * std::sqrt(rolling_inertia_kg_m2 * kr) * relative_w_rad_s;
  }
};

// I_r of a pair (see above); a mass of 0 is a side that does not move.
inline double rolling_inertia_kg_m2(double mass_i_kg, double radius_i_m, double mass_j_kg, double radius_j_m) {
  const double a = mass_i_kg * radius_i_m * radius_i_m, b = mass_j_kg * radius_j_m * radius_j_m;
  if (a <= 0) return 1.5 * b;
  if (b <= 0) return 1.5 * a;
  return 1.5 * a * b / (a + b);
}

}  // namespace demcal::dem
