// Parallel bond (Potyondy & Cundall 2004) in parallel with a linear contact.
//   parameters: {"modulus_pa", "kn_ks", "friction"                (linear part)
//                "bond_modulus_pa", "bond_kn_ks", "radius_multiplier" (lambda, default 1),
//                "tensile_strength_pa", "tensile_strength_std_pa" (default 0),
//                "shear_strength_pa", "shear_strength_std_pa"     (default 0)}
// Bond: R_b = lambda min(R_i, R_j), A = 2 R_b t, I = 2/3 R_b^3 t,
// kn_b = E_b / (R_i + R_j), ks_b = kn_b / (kn/ks)_b; forces and moment grow
// incrementally; it breaks in tension when -F_n/A + |M| R_b / I >= sigma_c,
// else in shear when |F_s| / A >= tau_c.
#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/linear_base.hpp"
#include "demcal/dem/bond_law.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

class ParallelBondModel : public LinearBase {
 public:
  ParallelBondModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        bond_modulus_pa_(positive(p, "bond_modulus_pa", where)),
        bond_kn_ks_(positive(p, "bond_kn_ks", where)),
        lambda_(p.contains("radius_multiplier") ? positive(p, "radius_multiplier", where) : 1.0),
        sigma_c_(non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        tau_c_(non_negative(p, "shear_strength_pa", where)),
        tau_c_std_(non_negative_or(p, "shear_strength_std_pa", 0.0, where)) {
    require_only(p, {"modulus_pa", "kn_ks", "friction", "bond_modulus_pa", "bond_kn_ks", "radius_multiplier",
                     "tensile_strength_pa", "tensile_strength_std_pa", "shear_strength_pa", "shear_strength_std_pa"},
                 where);
  }
  std::string name() const override { return "parallel_bond"; }

  bool install_bond(ContactSet& c, std::size_t k, const PairInfo& pair, double thickness_m, Rng& rng) const override {
    if (pair.wall) return false;
    const double rb = lambda_ * std::min(pair.radius_i, pair.radius_j);
    c.bond_radius[k] = rb;
    c.bond_area[k] = 2.0 * rb * thickness_m;
    c.bond_inertia[k] = 2.0 / 3.0 * rb * rb * rb * thickness_m;
    c.bond_kn[k] = bond_modulus_pa_ / (pair.radius_i + pair.radius_j);
    c.bond_ks[k] = c.bond_kn[k] / bond_kn_ks_;
    c.bond_fn[k] = c.bond_fs[k] = c.bond_m[k] = 0.0;
    c.strength_n[k] = draw_strength(sigma_c_, sigma_c_std_, rng);
    c.strength_s[k] = draw_strength(tau_c_, tau_c_std_, rng);
    c.flags[k] |= kBonded;
    return true;
  }

  void disk_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b,
                   const StepContext& step) const override {
    const double dt = step.dt_s;
    for_disk_pairs(
        c, begin, end, b,
        [&](std::size_t k, const Geometry& g) {
          PairForce f = linear_force(c, k, g, dt);
          if (!(c.flags[k] & kBonded)) return f;
          const double area = c.bond_area[k], inertia = c.bond_inertia[k];
          c.bond_fn[k] -= c.bond_kn[k] * area * g.vn * dt;
          c.bond_fs[k] -= c.bond_ks[k] * area * g.vs * dt;
          c.bond_m[k] -= c.bond_kn[k] * inertia * g.relative_w * dt;
          const double sigma = -c.bond_fn[k] / area + std::abs(c.bond_m[k]) * c.bond_radius[k] / inertia;
          const double tau = std::abs(c.bond_fs[k]) / area;
          if (sigma >= c.strength_n[k] || tau >= c.strength_s[k]) {
            break_bond(c, k, g, b, step, sigma >= c.strength_n[k] ? BreakMode::Tension : BreakMode::Shear);
            return f;
          }
          f.fn += c.bond_fn[k];
          f.fs += c.bond_fs[k];
          f.moment = c.bond_m[k];
          return f;
        },
        [&](std::size_t k, double gap) { return skip_unbonded_apart(c, k, gap); });
  }

  double normal_stiffness_estimate(double radius_m, double thickness_m) const override {
    const double rb = lambda_ * radius_m;
    return LinearBase::normal_stiffness_estimate(radius_m, thickness_m) +
           bond_modulus_pa_ / (2.0 * radius_m) * 2.0 * rb * thickness_m;
  }

 private:
  double bond_modulus_pa_, bond_kn_ks_, lambda_;
  double sigma_c_, sigma_c_std_, tau_c_, tau_c_std_;
};

}  // namespace

void register_parallel_bond_model(ContactModelRegistry& registry) {
  registry.add("parallel_bond", [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<ParallelBondModel>(p, where);
  });
}

}  // namespace demcal::dem
