// The Hertz-Mindlin (no-slip) contact in 3D, as EDEM and LIGGGHTS define it:
// with a = sqrt(R* delta) the contact radius,
//   normal   F = 4/3 E* sqrt(R*) delta^(3/2), stiffness S_n = 2 E* a,
//   shear    incremental, stiffness S_t = 8 G* a, a vector that turns with the
//            contact plane (linear_contact.hpp's rule), capped at mu F_n,
//   dashpots -2 sqrt(5/6) beta sqrt(S m*) v, beta = ln e / sqrt(ln^2 e + pi^2)
//            (Tsuji's form: the restitution e of a Hertz impact at any speed);
//            no tangential dashpot while sliding.
//   E* = 1 / ((1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2), G* = 1 / ((2 - nu_1)/G_1 + (2 - nu_2)/G_2),
//   R* = R_i R_j / (R_i + R_j) (R_i against a wall), m* likewise.
// The keys are the 2D model's (shear_modulus_pa, poisson, the second body's
// shear_modulus_2_pa and poisson_2, restitution, friction,
// time_step_overlap_ratio); cohesion and rolling resistance come with the
// powder's models.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/linear_contact.hpp"
#include "demcal/dem3d/pair_contact.hpp"

namespace demcal::dem3d {
namespace {

enum Column : std::size_t { kRadiusEff, kMassEff, kShearX, kShearY, kShearZ, kMaxContactRadius, kColumns };

double number(const nlohmann::json& p, const char* key, const std::string& where) {
  if (!p.contains(key)) throw Error(where + ": missing parameter \"" + key + "\"");
  if (!p.at(key).is_number() || !std::isfinite(p.at(key).get<double>()))
    throw Error(where + ": parameter \"" + key + "\" must be a finite number");
  return p.at(key).get<double>();
}

double positive(const nlohmann::json& p, const char* key, const std::string& where) {
  const double v = number(p, key, where);
  if (!(v > 0)) throw Error(where + ": " + key + " must be > 0 (got " + format_double(v) + ")");
  return v;
}

double poisson_of(const nlohmann::json& p, const char* key, const std::string& where) {
  const double nu = number(p, key, where);
  if (!(nu > -1.0 && nu < 0.5)) throw Error(where + ": " + key + " must lie in (-1, 0.5) (got " + format_double(nu) + ")");
  return nu;
}

class HertzMindlinModel : public ContactModel {
 public:
  HertzMindlinModel(const nlohmann::json& p, const std::string& where) {
    const double g1 = positive(p, "shear_modulus_pa", where);
    const double nu1 = poisson_of(p, "poisson", where);
    const double g2 = p.contains("shear_modulus_2_pa") ? positive(p, "shear_modulus_2_pa", where) : g1;
    const double nu2 = p.contains("poisson_2") ? poisson_of(p, "poisson_2", where) : nu1;
    const double e1 = 2 * g1 * (1 + nu1), e2 = 2 * g2 * (1 + nu2);
    e_eff_ = 1.0 / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
    g_eff_ = 1.0 / ((2 - nu1) / g1 + (2 - nu2) / g2);
    const double e = positive(p, "restitution", where);
    if (e > 1) throw Error(where + ": restitution must lie in (0, 1] (got " + format_double(e) + ")");
    const double log_e = std::log(e);
    damping_ = -2.0 * std::sqrt(5.0 / 6.0) * log_e / std::sqrt(log_e * log_e + M_PI * M_PI);
    friction_ = number(p, "friction", where);
    if (friction_ < 0) throw Error(where + ": friction must be >= 0");
    overlap_ratio_ = p.contains("time_step_overlap_ratio") ? positive(p, "time_step_overlap_ratio", where) : 0.01;
  }
  std::string name() const override { return "hertz_mindlin"; }
  std::vector<std::string> state_columns() const override {
    return {"radius_eff_m", "mass_eff_kg", "shear_force_x_n", "shear_force_y_n", "shear_force_z_n",
            "max_contact_radius_m"};
  }
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const override {
    const double ri = pair.radius_i, rj = pair.radius_j;
    c.column[kRadiusEff][k] = pair.wall ? ri : ri * rj / (ri + rj);
    const double mi = pair.mass_i_kg, mj = pair.mass_j_kg;
    c.column[kMassEff][k] = mi > 0 && mj > 0 ? mi * mj / (mi + mj) : std::max(mi, mj);
  }
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    for_sphere_pairs(
        c, s, [&](std::size_t k, const PairContact& p) { touch(c, k, out, p, step.dt_s); },
        [&](std::size_t k) { leave(c, k, out); });
  }
  void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                   const StepContext& step) const override {
    for_wall_pairs(
        c, s, g, [&](std::size_t k, const PairContact& p) { touch(c, k, out, p, step.dt_s); },
        [&](std::size_t k) { leave(c, k, out); });
  }
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    // Bounded by the springs at a contact radius of at least sqrt(ratio) R*
    // (an overlap of time_step_overlap_ratio R*), or the largest the pair has
    // reached, so the step does not shrink to nothing at first touch.
    const double radius = c.column[kRadiusEff][k];
    const double a = std::max(c.column[kMaxContactRadius][k], radius * std::sqrt(overlap_ratio_));
    const double sn = 2.0 * e_eff_ * a, st = 8.0 * g_eff_ * a;
    translational_n_m = std::max(sn, st);
    rotational_nm_rad = st * arm_m * arm_m;
  }
  double stiffness_estimate(double radius_m) const override {
    const double a = 0.5 * radius_m * std::sqrt(overlap_ratio_);  // two equal spheres: R* = r / 2
    return std::max(2.0 * e_eff_ * a, 8.0 * g_eff_ * a);
  }
  // Normal mode: zeta_n = sqrt(5/6) |beta| (the dashpot sized with the pair's
  // reduced mass m*). The tangential mode moves the surfaces, which the spin
  // makes 3.5 times lighter than m* for two equal spheres or a sphere on a
  // wall (1/m_t = 1/m_i + 1/m_j + R_i^2/I_i + R_j^2/I_j, I = 2/5 m R^2), so
  // its zeta is sqrt(3.5) times that.
  double max_damping_ratio() const override { return std::sqrt(3.5) * 0.5 * damping_; }
  bool depends_on_masses() const override { return true; }

 private:
  static void leave(PairBlock& c, std::size_t k, const PairForces& out) {
    c.column[kShearX][k] = c.column[kShearY][k] = c.column[kShearZ][k] = 0;
    c.flags[k] &= ~static_cast<dem::PairFlags>(dem::kTouching);
    out.set(k, {}, {}, {});
  }
  void touch(PairBlock& c, std::size_t k, const PairForces& out, const PairContact& p, double dt) const {
    const Vec3 n = p.normal, relative_velocity = p.relative_velocity_m_s, plane_spin = p.plane_spin_rad_s;
    const double overlap = p.overlap_m, arm_i = p.arm_i_m, arm_j = p.arm_j_m;
    const double radius = c.column[kRadiusEff][k], mass = c.column[kMassEff][k];
    const double a = std::sqrt(radius * overlap);
    const double sn = 2.0 * e_eff_ * a, st = 8.0 * g_eff_ * a;
    c.column[kMaxContactRadius][k] = std::max(c.column[kMaxContactRadius][k], a);
    const double elastic = 4.0 / 3.0 * e_eff_ * a * overlap;  // 4/3 E* sqrt(R*) delta^(3/2)
    const double vn = dot(relative_velocity, n);               // < 0 approaching
    // The dashpot may pull at the end of an impact: clipping it would change e.
    const double normal = elastic - damping_ * std::sqrt(sn * mass) * vn;
    const Vec3 vt = relative_velocity - vn * n;
    // The stored shear spring, turned with the contact plane, incremented, capped.
    Vec3 spring = turned_shear({c.column[kShearX][k], c.column[kShearY][k], c.column[kShearZ][k]}, n, plane_spin, dt);
    spring = spring + (st * dt) * vt;
    const double limit = friction_ * elastic, size = norm(spring);
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
    out.set(k, force, arm_i * n_cross_fs, arm_j * n_cross_fs);
  }

  double e_eff_ = 0, g_eff_ = 0, damping_ = 0, friction_ = 0, overlap_ratio_ = 0.01;
};

}  // namespace

void register_hertz_mindlin_model(ContactModelRegistry& registry) {
  registry.add("hertz_mindlin",
               {"shear_modulus_pa", "poisson", "shear_modulus_2_pa", "poisson_2", "restitution", "friction",
                "time_step_overlap_ratio"},
               [](const nlohmann::json& p, const std::string& where) {
                 return std::make_unique<HertzMindlinModel>(p, where);
               });
  // LIGGGHTS's granular Hertz model (the wall's material is a second atom type there).
  registry.set_peer_names("hertz_mindlin", nlohmann::json::parse(R"({
    "liggghts": {"model": "hertz", "notes": ["the wall material (shear_modulus_2_pa, poisson_2) is a second atom type in LIGGGHTS: add its column yourself"],
      "keywords": [{"key": "shear_modulus_pa", "name": "youngsModulus", "as": "youngs_modulus", "with": "poisson"},
                   {"key": "poisson", "name": "poissonsRatio"},
                   {"key": "restitution", "name": "coefficientRestitution", "per": "pair"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem3d
