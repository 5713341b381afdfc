// LIGGGHTS' simplified JKR cohesion ("cohesion sjkr") on the 3D Hertz-Mindlin
// family (hertz_base.hpp): while two spheres overlap, an attraction k A along
// the normal, k the cohesion energy density (J/m^3) and A the area of the
// circle where the spheres' surfaces cross,
//   A = -pi/4 (d - R_i - R_j)(d + R_i - R_j)(d - R_i + R_j)(d + R_i + R_j) / d^2
// at centre distance d (against a wall: pi (R^2 - h^2), h the centre's
// distance to it). No force across a gap, no hysteresis. As in LIGGGHTS it
// lowers the normal force; unlike LIGGGHTS (whose friction and rolling limits
// take |F_n| with the damping and the cohesion in it) friction and rolling
// resistance here take the repulsive Hertz part, as the jkr model does: state
// that when comparing the two codes.
//   parameters: the family's and "cohesion_energy_density_j_m3" (k >= 0).
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/hertz_base.hpp"

namespace demcal::dem3d {
namespace {

class SjkrModel : public HertzBase {
 public:
  SjkrModel(const nlohmann::json& p, const std::string& where)
      : HertzBase(p, where), energy_density_j_m3_(dem::non_negative(p, "cohesion_energy_density_j_m3", where)) {}
  std::string name() const override { return "sjkr"; }

  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    overlapping_sphere_pairs(c, s, out, step.dt_s, [&](std::size_t k, const PairContact& p) {
      const double ri = s.radius[static_cast<std::size_t>(c.i[k])], rj = s.radius[static_cast<std::size_t>(c.j[k])];
      const double d = ri + rj - p.overlap_m;
      const double area = -M_PI / 4 * ((d - ri - rj) * (d + ri - rj) * (d - ri + rj) * (d + ri + rj)) / (d * d);
      return normal(c, k, p, area);
    });
  }
  void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                   const StepContext& step) const override {
    overlapping_wall_pairs(c, s, g, out, step.dt_s, [&](std::size_t k, const PairContact& p) {
      const double r = s.radius[static_cast<std::size_t>(c.i[k])], h = r - p.overlap_m;
      return normal(c, k, p, M_PI * (r * r - h * h));
    });
  }

 private:
  NormalForce normal(const PairBlock& c, std::size_t k, const PairContact& p, double area_m2) const {
    NormalForce f;
    f.contact_radius_m = std::sqrt(c.column[kRadiusEff][k] * p.overlap_m);
    f.repulsive_n = 4.0 / 3.0 * e_eff_pa_ * f.contact_radius_m * p.overlap_m;
    f.total_n = f.repulsive_n - energy_density_j_m3_ * area_m2;
    return f;
  }

  double energy_density_j_m3_;
};

}  // namespace

void register_sjkr_model(ContactModelRegistry& registry) {
  registry.add("sjkr", hertz_parameter_keys({"cohesion_energy_density_j_m3"}),
               [](const nlohmann::json& p, const std::string& where) { return std::make_unique<SjkrModel>(p, where); });
  // LIGGGHTS: model hertz, cohesion sjkr, rolling cdt (its relative form).
  registry.set_peer_names("sjkr", nlohmann::json::parse(R"({
    "liggghts": {"model": "hertz", "notes": ["pair style gran model hertz tangential history cohesion sjkr; LIGGGHTS' friction limit takes |F_n| with the damping and the cohesion in it, ours the repulsive Hertz part", "the wall material (shear_modulus_2_pa, poisson_2) is a second atom type in LIGGGHTS: add its column yourself"],
      "keywords": [{"key": "shear_modulus_pa", "name": "youngsModulus", "as": "youngs_modulus", "with": "poisson"},
                   {"key": "poisson", "name": "poissonsRatio"},
                   {"key": "restitution", "name": "coefficientRestitution", "per": "pair"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"},
                   {"key": "cohesion_energy_density_j_m3", "name": "cohesionEnergyDensity", "per": "pair"},
                   {"key": "rolling_friction_cdt_relative", "name": "coefficientRollingFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem3d
