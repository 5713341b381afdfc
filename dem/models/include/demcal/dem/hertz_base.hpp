#pragma once
// What the Hertz-Mindlin and JKR models share: the Hertz-Mindlin (no-slip)
// springs and dashpots, Coulomb friction, rolling resistance, and their
// per-pair state. The models differ only in the normal force (Hertz, or JKR's
// adhesive curve with its hysteresis), which each supplies to hertz_force().
//
// 2D convention: each disk is treated as the sphere of its radius for the
// contact law (as 2D codes do for Hertz and JKR), while its mass is the
// disk's, per unit thickness as everywhere in the engine. So forces are a
// sphere's while inertia is a disk's: the adhesion-to-weight ratio of a 2D
// model depends on the thickness (docs/explanation/contact_models.md).
//
// With a = the contact radius (sqrt(R* delta) for Hertz):
//   normal stiffness  S_n = 2 E* a,  tangential S_t = 8 G* a,
//   dashpots  -2 sqrt(5/6) beta sqrt(S m*) v, beta = ln e / sqrt(ln^2 e + pi^2)
//   (EDEM's and Tsuji's form, which gives the coefficient of restitution e
//   of a Hertz impact at any speed), shear spring incremental, capped at
//   mu F_rep (F_rep the repulsive part of the normal force), no tangential
//   dashpot while sliding.
//   E* = 1 / ((1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2), G* = 1 / ((2 - nu_1)/G_1 + (2 - nu_2)/G_2),
//   R* = R_i R_j / (R_i + R_j) (R_i against a wall), m* likewise (m_i against a wall).
//   parameters: {"shear_modulus_pa", "poisson" (the first body's material),
//                "shear_modulus_2_pa", "poisson_2" (the second's, e.g. a wall's; default the first's),
//                "restitution" (0 < e <= 1), "friction" (mu),
//                rolling resistance (rolling_resistance.hpp, optional),
//                "time_step_overlap_ratio" (default 0.01, see stiffness())}
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/contact_geometry.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/hertz_material.hpp"
#include "demcal/dem/rolling_resistance.hpp"

namespace demcal::dem {

enum HertzColumn : std::size_t {
  kRadiusEff = 0,      // R*, m
  kMassEff,            // m*, kg (0: both sides immovable)
  kRollingInertia,     // I_r, kg m^2
  kHertzShearForce,    // elastic shear force along t, N
  kRollingMoment,      // elastic rolling couple on j (epsd), N m
  kContactRadius,      // a now, m (0 when apart)
  kMaxContactRadius,   // the largest a this pair reached, m (time step)
  kNormalVelocity,     // the normal relative velocity the last step saw (half a step behind), m/s
  kHertzColumns
};

// The normal force a model computes for a touching pair.
struct NormalForce {
  double total_n = 0;      // elastic normal force (adhesion included), N
  double repulsive_n = 0;  // its repulsive part, which friction and rolling resistance use, N
  double contact_radius_m = 0;
};


class HertzBase : public ContactModel {
 public:
  HertzBase(const nlohmann::json& p, const std::string& where);

  std::vector<std::string> state_columns() const override;
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m) const override;
  // The step is bounded by the springs at a contact radius of at least
  // sqrt(ratio) R* (an overlap of `time_step_overlap_ratio` R*), or the
  // largest the pair has reached, so it does not shrink to nothing at first touch.
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override;
  double normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const override;
  double stiffness_estimate(double radius_m, double thickness_m) const override;
  bool depends_on_masses() const override { return true; }
  // The dashpots are sized with the pair's reduced mass m* (m/2 for two equal
  // disks, m against a wall), the normal mode's own mass: zeta_n =
  // sqrt(5/6) |beta|. The tangential mode moves the disks' surfaces, which
  // their spin makes three times lighter (m/6 for two equal disks: 1/m_t =
  // 2/m + 2 r^2/I; m/3 against a wall), so its zeta is sqrt(3) times that:
  // 1.58 |beta|. Rolling damping (type C) adds eta_r.
  double max_damping_ratio() const override;
  // Type A rolling resistance: each touching pair can give each of its disks
  // mu_r R_i F_rep against its own spin (F_rep = 4 E* a^3 / (3 R*), the
  // repulsive part of the normal force, from the pair's contact radius).
  bool adds_rolling_limits() const override { return rolling_.type == RollingResistance::Type::Cdt; }
  void add_rolling_limits(const ConstPairBlock& c, const Bodies& b, bool walls, double* limit_nm) const override;

  double effective_modulus_pa() const { return e_eff_pa_; }
  double effective_shear_modulus_pa() const { return g_eff_pa_; }

 protected:
  // Pair k's forces once its model has the normal force; updates its state.
  PairForce hertz_force(const PairBlock& c, std::size_t k, const Geometry& g, double dt_s, const NormalForce& n) const;
  // Forgets a pair's contact (apart): shear spring, rolling couple, contact radius.
  static void release(const PairBlock& c, std::size_t k);

  double e_eff_pa_ = 0, g_eff_pa_ = 0, friction_ = 0;
  double damping_ = 0;  // -2 sqrt(5/6) beta, >= 0
  double overlap_ratio_ = 0.01;
  RollingResistance rolling_;
};

// beta of the restitution dashpot, ln e / sqrt(ln^2 e + pi^2) (<= 0).
double restitution_beta(double restitution);

}  // namespace demcal::dem
