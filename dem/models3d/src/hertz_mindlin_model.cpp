// The Hertz-Mindlin (no-slip) contact in 3D, as EDEM and LIGGGHTS define it
// (hertz_base.hpp): the normal force F = 4/3 E* sqrt(R*) delta^(3/2) with
// a = sqrt(R* delta), on the family's springs, dashpots, friction and rolling
// resistance. The keys are the 2D model's (shear_modulus_pa, poisson, the
// second body's shear_modulus_2_pa and poisson_2, restitution, friction,
// time_step_overlap_ratio, the rolling keys).
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/hertz_base.hpp"

namespace demcal::dem3d {
namespace {

class HertzMindlinModel : public HertzBase {
 public:
  using HertzBase::HertzBase;
  std::string name() const override { return "hertz_mindlin"; }
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    overlapping_sphere_pairs(c, s, out, step.dt_s, [&](std::size_t k, const PairContact& p) { return normal(c, k, p); });
  }
  void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                   const StepContext& step) const override {
    overlapping_wall_pairs(c, s, g, out, step.dt_s,
                           [&](std::size_t k, const PairContact& p) { return normal(c, k, p); });
  }

 private:
  NormalForce normal(const PairBlock& c, std::size_t k, const PairContact& p) const {
    NormalForce f;
    f.contact_radius_m = std::sqrt(c.column[kRadiusEff][k] * p.overlap_m);
    f.repulsive_n = f.total_n = 4.0 / 3.0 * e_eff_pa_ * f.contact_radius_m * p.overlap_m;  // 4/3 E* sqrt(R*) delta^(3/2)
    return f;
  }
};

}  // namespace

void register_hertz_mindlin_model(ContactModelRegistry& registry) {
  registry.add("hertz_mindlin", hertz_parameter_keys({}), [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<HertzMindlinModel>(p, where);
  });
  // LIGGGHTS's granular Hertz model (the wall's material is a second atom type there).
  registry.set_peer_names("hertz_mindlin", nlohmann::json::parse(R"({
    "liggghts": {"model": "hertz", "notes": ["the wall material (shear_modulus_2_pa, poisson_2) is a second atom type in LIGGGHTS: add its column yourself"],
      "keywords": [{"key": "shear_modulus_pa", "name": "youngsModulus", "as": "youngs_modulus", "with": "poisson"},
                   {"key": "poisson", "name": "poissonsRatio"},
                   {"key": "restitution", "name": "coefficientRestitution", "per": "pair"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"},
                   {"key": "rolling_friction_cdt_relative", "name": "coefficientRollingFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem3d
