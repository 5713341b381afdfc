// Hertz-Mindlin (no slip) for unbonded grains: F_n = 4/3 E* sqrt(R*) delta^(3/2)
// with the dashpot that gives the set coefficient of restitution, Mindlin's
// tangential spring 8 G* a capped by Coulomb friction, optional rolling
// resistance; the same law against walls (hertz_base.hpp).
//   parameters: those of hertz_base.hpp.
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/hertz_base.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

class HertzMindlinModel : public HertzBase {
 public:
  HertzMindlinModel(const nlohmann::json& p, const std::string& where) : HertzBase(p, where) {
  }
  std::string name() const override { return "hertz_mindlin"; }

  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    for_disk_pairs(c, b, step, [&](std::size_t k, const Geometry& g) { return force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return apart(c, k, gap); });
  }
  void wall_forces(PairBlock& c, Bodies& b, std::vector<Wall>& walls, const StepContext& step) const override {
    for_wall_pairs(c, b, walls, [&](std::size_t k, const Geometry& g) { return force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return apart(c, k, gap); });
  }

 private:
  static bool apart(const PairBlock& c, std::size_t k, double gap) {
    if (gap < 0) return false;
    release(c, k);
    return true;
  }
  PairForce force(const PairBlock& c, std::size_t k, const Geometry& g, double dt_s) const {
    NormalForce n;
    n.contact_radius_m = std::sqrt(c.column[kRadiusEff][k] * g.overlap);
    n.total_n = 4.0 / 3.0 * e_eff_pa_ * n.contact_radius_m * n.contact_radius_m * n.contact_radius_m /
                c.column[kRadiusEff][k];
    n.repulsive_n = n.total_n;
    return hertz_force(c, k, g, dt_s, n);
  }
};

}  // namespace

void register_hertz_mindlin_model(ContactModelRegistry& registry) {
  registry.add("hertz_mindlin", hertz_parameter_keys({}), [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<HertzMindlinModel>(p, where);
  });
  // LIGGGHTS's granular Hertz model; its rolling_friction cdt is the relative
  // form. The wall's own material (the *_2 keys) is a second atom type there.
  registry.set_peer_names("hertz_mindlin", nlohmann::json::parse(R"({
    "liggghts": {"model": "hertz", "notes": ["the wall material (shear_modulus_2_pa, poisson_2) is a second atom type in LIGGGHTS: add its column yourself"],
      "keywords": [{"key": "shear_modulus_pa", "name": "youngsModulus", "as": "youngs_modulus", "with": "poisson"},
                   {"key": "poisson", "name": "poissonsRatio"},
                   {"key": "restitution", "name": "coefficientRestitution", "per": "pair"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"},
                   {"key": "rolling_friction_cdt_relative", "name": "coefficientRollingFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem
