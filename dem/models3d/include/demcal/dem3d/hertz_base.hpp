#pragma once
// What the 3D Hertz-Mindlin family shares (hertz_mindlin, jkr, sjkr): the
// Hertz-Mindlin (no-slip) springs and dashpots, Coulomb friction, rolling
// resistance and their per-pair state. A model supplies the normal force
// (Hertz's, JKR's adhesive curve, or Hertz's less LIGGGHTS' sjkr cohesion)
// and which listed pairs are in contact.
//
// With a the contact radius (sqrt(R* delta) for Hertz):
//   normal stiffness S_n = 2 E* a, tangential S_t = 8 G* a,
//   dashpots -2 sqrt(5/6) beta sqrt(S m*) v, beta = ln e / sqrt(ln^2 e + pi^2)
//   (Tsuji's form: the restitution e of a Hertz impact at any speed);
//   shear spring incremental, a vector that turns with the contact plane
//   (linear_contact.hpp's rule), capped at mu F_rep (F_rep the repulsive part
//   of the normal force); no tangential dashpot while sliding.
//   E* = 1 / ((1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2), G* = 1 / ((2 - nu_1)/G_1 + (2 - nu_2)/G_2),
//   R* = R_i R_j / (R_i + R_j) (R_i against a wall), m* likewise.
// Rolling resistance (demcal/dem/rolling_resistance.hpp, the 2D keys) in 3D:
//   type C (epsd): a couple vector on j (its opposite on i) that turns with the
//     contact plane, grows by -k_r dt times the rolling part of j's spin
//     relative to i's (the part across the normal: twisting is not resisted),
//     capped at mu_r R* F_rep, with the dashpot -C_r w_roll while below the
//     cap; I_r = 1.4 (m_i R_i^2)(m_j R_j^2) / (m_i R_i^2 + m_j R_j^2), the
//     spheres' inertia about their contact points (1.4 m R^2 against a wall);
//   type A (cdt): each touching pair can give each of its spheres a couple of
//     up to mu_r R_i F_rep against that sphere's own spin; the world applies
//     the sum as Coulomb friction in rotation (static resistance included);
//   type A relative (LIGGGHTS' cdt): -mu_r R* F_rep w_roll / max(|w_roll|, threshold).
// A wall is taken as not spinning for the rolling couple of types C and A
// relative.
//   parameters: {"shear_modulus_pa", "poisson", "shear_modulus_2_pa",
//                "poisson_2", "restitution", "friction",
//                "time_step_overlap_ratio" (default 0.01, see stiffness()),
//                the rolling keys}, and a model's own.
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/hertz_material.hpp"
#include "demcal/dem/rolling_resistance.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/pair_contact.hpp"

namespace demcal::dem3d {

enum HertzColumn : std::size_t {
  kRadiusEff,         // R*, m
  kMassEff,           // m*, kg
  kShearX,            // elastic shear force on i, N
  kShearY,
  kShearZ,
  kMaxContactRadius,  // the largest a this pair reached, m (time step)
  kRollingInertia,    // I_r, kg m^2
  kRollingX,          // elastic rolling couple on j (epsd), N m
  kRollingY,
  kRollingZ,
  kContactRadius,     // a now, m (0 when apart)
  kNormalVelocity,    // the normal relative velocity the last step saw (half a step behind), m/s
  kHertzColumns
};

// The normal force a model computes for a pair in contact.
struct NormalForce {
  double total_n = 0;           // elastic normal force (adhesion included), N
  double repulsive_n = 0;       // its repulsive part, which friction and rolling resistance use, N
  double contact_radius_m = 0;  // a
};

using dem::hertz_parameter_keys;

// I_r of a pair of spheres (see above); a mass of 0 is a side that does not move.
double sphere_rolling_inertia_kg_m2(double mass_i_kg, double radius_i_m, double mass_j_kg, double radius_j_m);

class HertzBase : public ContactModel {
 public:
  HertzBase(const nlohmann::json& p, const std::string& where);

  std::vector<std::string> state_columns() const override;
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const override;
  // The step is bounded by the springs at a contact radius of at least
  // sqrt(ratio) R* (an overlap of time_step_overlap_ratio R*), or the largest
  // the pair has reached, so it does not shrink to nothing at first touch.
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override;
  double stiffness_estimate(double radius_m) const override;
  // Normal mode: zeta_n = sqrt(5/6) |beta| (the dashpot sized with the pair's
  // reduced mass m*). The tangential mode moves the surfaces, which the spin
  // makes 3.5 times lighter than m* for two equal spheres or a sphere on a
  // wall (1/m_t = 1/m_i + 1/m_j + R_i^2/I_i + R_j^2/I_j, I = 2/5 m R^2), so
  // its zeta is sqrt(3.5) times that. Rolling damping (type C) adds eta_r.
  double max_damping_ratio() const override;
  bool depends_on_masses() const override { return true; }
  bool adds_rolling_limits() const override { return rolling_.type == dem::RollingResistance::Type::Cdt; }
  void add_rolling_limits(const ConstPairBlock& c, const Spheres& s, bool walls, double* limit_nm) const override;

  double effective_modulus_pa() const { return e_eff_pa_; }

 protected:
  // The forces of the block's pair k in contact, once its model has the
  // normal force; updates its state. `radius_j_m` is 0 for a wall. `spin_i`
  // and `spin_j` are the spheres' spins (a wall's: zero).
  void hertz_touch(PairBlock& c, std::size_t k, const PairForces& out, const PairContact& p, double dt_s,
                   const NormalForce& n, Vec3 spin_i, Vec3 spin_j) const;
  // A pair out of contact: no force, its springs and contact radius forgotten.
  static void release(PairBlock& c, std::size_t k, const PairForces& out);
  // A block whose pairs are in contact while their spheres overlap (no
  // hysteresis): hertz_touch with the normal force `normal(k, contact)`
  // gives, release for a pair apart.
  template <class Normal>
  void overlapping_sphere_pairs(PairBlock& c, const Spheres& s, const PairForces& out, double dt_s, Normal normal) const {
    for_sphere_pairs(
        c, s,
        [&](std::size_t k, const PairContact& p) {
          const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
          hertz_touch(c, k, out, p, dt_s, normal(k, p), s.spin(i), s.spin(j));
        },
        [&](std::size_t k) { release(c, k, out); });
  }
  template <class Normal>
  void overlapping_wall_pairs(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                              double dt_s, Normal normal) const {
    for_wall_pairs(
        c, s, g,
        [&](std::size_t k, const PairContact& p) {
          hertz_touch(c, k, out, p, dt_s, normal(k, p), s.spin(static_cast<std::size_t>(c.i[k])), {});
        },
        [&](std::size_t k) { release(c, k, out); });
  }

  double e_eff_pa_ = 0, g_eff_pa_ = 0, friction_ = 0;
  double damping_ = 0;  // -2 sqrt(5/6) beta, >= 0
  double overlap_ratio_ = 0.01;
  dem::RollingResistance rolling_;
};

}  // namespace demcal::dem3d
