// Linear parallel bond in 3D (Potyondy & Cundall 2004; PFC3D's linearpbond)
// in parallel with a linear contact.
//   parameters: the linear model's, and "bond_modulus_pa", "bond_kn_ks",
//               "radius_multiplier" (lambda, default 1), "tensile_strength_pa",
//               "tensile_strength_std_pa" (default 0), "shear_strength_pa",
//               "shear_strength_std_pa" (default 0), "moment_contribution"
//               (beta, default 1)
// Bond: a cement disc of radius R_b = lambda min(R_i, R_j), A = pi R_b^2,
// I = pi R_b^4 / 4, J = pi R_b^4 / 2; kn_b = E_b / (R_i + R_j) and
// ks_b = kn_b / (kn/ks)_b per area. Its normal force, shear force vector,
// twisting moment and bending moment vector grow incrementally from zero at
// installation (the shear force and the bending moment turn with the contact
// plane, as the linear contact's shear force). It breaks in tension when
// sigma = -F_n / A + beta |M_b| R_b / I >= sigma_c, else in shear when
// tau = |F_s| / A + beta |M_t| R_b / J >= tau_c (PFC's pb_fa 0: no friction
// angle), and is gone: the linear contact alone remains.
//   state: the linear columns, then the bond's stiffnesses per area, radius,
//   forces and moments (on i) and the strengths drawn for it.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/linear_base.hpp"

namespace demcal::dem3d {
namespace {

enum BondColumn : std::size_t {
  kBondKn = kLinearColumns,  // normal stiffness per area, Pa/m
  kBondKs,                   // shear stiffness per area, Pa/m
  kBondRadius,               // m
  kBondFn,                   // normal force, compression > 0, N
  kBondFsX,                  // shear force on i, N
  kBondFsY,
  kBondFsZ,
  kBondMt,                   // twisting moment on i about the normal, N m
  kBondMbX,                  // bending moment on i, N m
  kBondMbY,
  kBondMbZ,
  kTensileStrength,          // Pa
  kShearStrength,            // Pa
};

struct Section {
  double area, inertia, polar;  // A, I, J
};
inline Section section_of(double rb) {
  const double rb2 = rb * rb;
  return {M_PI * rb2, 0.25 * M_PI * rb2 * rb2, 0.5 * M_PI * rb2 * rb2};
}

class ParallelBondModel : public LinearBase {
 public:
  ParallelBondModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        bond_modulus_pa_(dem::positive(p, "bond_modulus_pa", where)),
        bond_kn_ks_(dem::positive(p, "bond_kn_ks", where)),
        lambda_(p.contains("radius_multiplier") ? dem::positive(p, "radius_multiplier", where) : 1.0),
        sigma_c_(dem::non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(dem::non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        tau_c_(dem::non_negative(p, "shear_strength_pa", where)),
        tau_c_std_(dem::non_negative_or(p, "shear_strength_std_pa", 0.0, where)),
        beta_(dem::non_negative_or(p, "moment_contribution", 1.0, where)) {
    if (beta_ > 1) throw Error(where + ": moment_contribution must lie in [0, 1]");
  }
  std::string name() const override { return "parallel_bond"; }
  bool has_bonds() const override { return true; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"bond_kn_pa_m", "bond_ks_pa_m", "bond_radius_m", "bond_normal_force_n",
                          "bond_shear_force_x_n", "bond_shear_force_y_n", "bond_shear_force_z_n",
                          "bond_twisting_moment_nm", "bond_bending_moment_x_nm", "bond_bending_moment_y_nm",
                          "bond_bending_moment_z_nm", "bond_tensile_strength_pa", "bond_shear_strength_pa"})
      columns.emplace_back(c);
    return columns;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, Rng& rng) const override {
    if (pair.wall) return false;
    c.column[kBondRadius][k] = lambda_ * std::min(pair.radius_i, pair.radius_j);
    c.column[kBondKn][k] = bond_modulus_pa_ / (pair.radius_i + pair.radius_j);
    c.column[kBondKs][k] = c.column[kBondKn][k] / bond_kn_ks_;
    for (std::size_t column = kBondFn; column <= kBondMbZ; ++column) c.column[column][k] = 0.0;
    c.column[kTensileStrength][k] = dem::draw_strength(sigma_c_, sigma_c_std_, rng);
    c.column[kShearStrength][k] = dem::draw_strength(tau_c_, tau_c_std_, rng);
    c.flags[k] |= dem::kBonded;
    return true;
  }

  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    for_bondable_pairs(c, s, out, step.dt_s,
                       [&](std::size_t k, const PairContact& p) { bonded(c, k, s, out, p, step.dt_s); });
  }

  // The bond's springs in parallel with the contact's (kept after a break,
  // as a bound on the step): translation by the stiffer of the normal and
  // shear sums; rotation by the shear sum at the contact point plus the
  // stiffer of the bond's bending and twisting springs.
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    const Section b = section_of(c.column[kBondRadius][k]);
    const double normal = c.column[kKn][k] + c.column[kBondKn][k] * b.area;
    const double shear = c.column[kKs][k] + c.column[kBondKs][k] * b.area;
    translational_n_m = std::max(normal, shear);
    rotational_nm_rad =
        shear * arm_m * arm_m + std::max(c.column[kBondKn][k] * b.inertia, c.column[kBondKs][k] * b.polar);
  }
  double stiffness_estimate(double radius_m) const override {
    const double bond_kn = bond_modulus_pa_ / (2.0 * radius_m) * section_of(lambda_ * radius_m).area;
    return LinearBase::stiffness_estimate(radius_m) + bond_kn * std::max(1.0, 1.0 / bond_kn_ks_);
  }

  double max_bond_utilisation(const ConstPairBlock& c, const Spheres&) const override {
    double most = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      if (!(c.flags[k] & dem::kBonded)) continue;
      double sigma = 0, tau = 0;
      stresses(c, k, sigma, tau);
      most = std::max({most, dem::utilisation(sigma, c.column[kTensileStrength][k]),
                       dem::utilisation(tau, c.column[kShearStrength][k])});
    }
    return most;
  }

 private:
  template <class Block>
  void stresses(const Block& c, std::size_t k, double& sigma, double& tau) const {
    const double rb = c.column[kBondRadius][k];
    const Section b = section_of(rb);
    const Vec3 fs{c.column[kBondFsX][k], c.column[kBondFsY][k], c.column[kBondFsZ][k]};
    const Vec3 mb{c.column[kBondMbX][k], c.column[kBondMbY][k], c.column[kBondMbZ][k]};
    sigma = -c.column[kBondFn][k] / b.area + beta_ * norm(mb) * rb / b.inertia;
    tau = norm(fs) / b.area + beta_ * std::abs(c.column[kBondMt][k]) * rb / b.polar;
  }

  void bonded(PairBlock& c, std::size_t k, const Spheres& s, const PairForces& out, const PairContact& p,
              double dt_s) const {
    // The linear contact, while the spheres touch.
    double fn = 0;
    Vec3 fs;
    const bool touching = p.overlap_m > 0;
    if (touching)
      fs = linear_forces(c, k, p, dt_s, fn);
    else
      forget_shear(c, k);
    // The bond's increments: j's motion relative to i's.
    const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
    const Section b = section_of(c.column[kBondRadius][k]);
    const double kn_b = c.column[kBondKn][k], ks_b = c.column[kBondKs][k];
    const Vec3 n = p.normal;
    const double bond_fn = c.column[kBondFn][k] - kn_b * b.area * dot(p.relative_velocity_m_s, n) * dt_s;
    const Vec3 bond_fs = incremented_shear({c.column[kBondFsX][k], c.column[kBondFsY][k], c.column[kBondFsZ][k]}, n,
                                           p.plane_spin_rad_s, dt_s, p.relative_velocity_m_s, ks_b * b.area * dt_s);
    const Vec3 relative_spin = s.spin(j) - s.spin(i);
    const double bond_mt = c.column[kBondMt][k] + ks_b * b.polar * dot(relative_spin, n) * dt_s;
    const Vec3 bond_mb = incremented_shear({c.column[kBondMbX][k], c.column[kBondMbY][k], c.column[kBondMbZ][k]}, n,
                                           p.plane_spin_rad_s, dt_s, relative_spin, kn_b * b.inertia * dt_s);
    c.column[kBondFn][k] = bond_fn;
    c.column[kBondFsX][k] = bond_fs.x, c.column[kBondFsY][k] = bond_fs.y, c.column[kBondFsZ][k] = bond_fs.z;
    c.column[kBondMt][k] = bond_mt;
    c.column[kBondMbX][k] = bond_mb.x, c.column[kBondMbY][k] = bond_mb.y, c.column[kBondMbZ][k] = bond_mb.z;
    double sigma = 0, tau = 0;
    stresses(c, k, sigma, tau);
    const bool tension = sigma >= c.column[kTensileStrength][k];
    const bool broke = tension || tau >= c.column[kShearStrength][k];
    dem::PairFlags flags = c.flags[k] & ~static_cast<dem::PairFlags>(dem::kTouching);
    if (touching) flags |= dem::kTouching;
    if (broke) {
      flags = mark_break(flags & ~static_cast<dem::PairFlags>(dem::kBonded), tension);
      for (std::size_t column = kBondFn; column <= kBondMbZ; ++column) c.column[column][k] = 0.0;
      c.flags[k] = flags;
      set_contact_force(out, k, p, fs - fn * n, fs);
      return;
    }
    c.flags[k] = flags;
    const Vec3 shear = fs + bond_fs;
    set_contact_force(out, k, p, shear - (fn + bond_fn) * n, shear, bond_mt * n + bond_mb);
  }

  double bond_modulus_pa_, bond_kn_ks_, lambda_;
  double sigma_c_, sigma_c_std_, tau_c_, tau_c_std_, beta_;
};

}  // namespace

void register_parallel_bond_model(ContactModelRegistry& registry) {
  registry.add("parallel_bond", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction", "bond_modulus_pa",
                                 "bond_kn_ks", "radius_multiplier", "tensile_strength_pa", "tensile_strength_std_pa",
                                 "shear_strength_pa", "shear_strength_std_pa", "moment_contribution"},
               [](const nlohmann::json& p, const std::string& where) {
                 return std::make_unique<ParallelBondModel>(p, where);
               });
  // PFC3D's linearpbond (pb_fa 0: this bond has no friction angle).
  registry.set_peer_names("parallel_bond", nlohmann::json::parse(R"({
    "pfc": {"model": "linearpbond",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "kn_n_m", "group": "property", "name": "kn"},
                   {"key": "ks_n_m", "group": "property", "name": "ks"},
                   {"key": "bond_modulus_pa", "group": "pb_deformability", "name": "emod"},
                   {"key": "bond_kn_ks", "group": "pb_deformability", "name": "kratio"},
                   {"key": "friction", "group": "property", "name": "fric"},
                   {"key": "tensile_strength_pa", "group": "property", "name": "pb_ten"},
                   {"key": "shear_strength_pa", "group": "property", "name": "pb_coh"},
                   {"group": "property", "name": "pb_fa", "value": 0},
                   {"key": "radius_multiplier", "group": "property", "name": "pb_rmul", "default": 1},
                   {"key": "moment_contribution", "group": "property", "name": "pb_mcf", "default": 1}]},
    "yade": {"model": "CohFrictMat", "notes": ["YADE sets its normal stiffness from young as 2 young R1 R2 / (R1 + R2) (PFC3D: pi min(R)^2 E / (R1 + R2)) and its cohesions over its own area: the same numbers make a stiffer or softer material there; check a YADE run against demcal's"],
      "keywords": [{"key": "modulus_pa", "name": "young"}, {"key": "kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "friction", "name": "frictionAngle", "as": "atan"},
                   {"key": "tensile_strength_pa", "name": "normalCohesion"},
                   {"key": "shear_strength_pa", "name": "shearCohesion"}, {"name": "isCohesive", "value": true}]}})"));
}

}  // namespace demcal::dem3d
