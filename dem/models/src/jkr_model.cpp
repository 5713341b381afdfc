// JKR cohesion on Hertz-Mindlin (hertz_base.hpp), parameterised by the work of
// adhesion w (J/m^2), the energy per area to separate two surfaces: the curve
// of jkr_curve.hpp (shared with 3D), whose least force is the classic pull-off
// -1.5 pi w R*. Codes that write
// the same law with a surface energy gamma mean gamma = w / 2 (LAMMPS: pull-off
// 3 pi gamma R); EDEM documents 1.5 pi gamma R* with that law, so its gamma is
// our w or off by two: convert with care (docs/explanation/contact_models.md).
// Hysteresis: a pair's contact forms when the disks touch (delta >= 0) and
// holds, pulling, until the separation at which the curve ends,
// delta_c = -delta(a_c), a_c = (pi w R*^2 / (8 E*))^(1/3); friction and rolling
// resistance use the repulsive part 4 E* a^3 / (3 R*). With w = 0 it is Hertz.
// The neighbour list's skin must exceed delta_c: the model states it for its
// largest pairs (attachment_gap_m) and the world checks (delta_c is about 1e-3
// to 1e-2 R* for powders, the default skin 0.25 of the mean radius).
//   parameters: those of hertz_base.hpp and "work_of_adhesion_j_m2" (w >= 0).
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/hertz_base.hpp"
#include "demcal/dem/jkr_curve.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

constexpr std::size_t kSeparationLimit = kHertzColumns;  // delta_c, m

class JkrModel : public HertzBase {
 public:
  JkrModel(const nlohmann::json& p, const std::string& where)
      : HertzBase(p, where), curve_(e_eff_pa_, non_negative(p, "work_of_adhesion_j_m2", where)) {}
  std::string name() const override { return "jkr"; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = HertzBase::state_columns();
    columns.push_back("separation_limit_m");
    return columns;
  }
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m) const override {
    HertzBase::initialise(c, k, pair, thickness_m);
    c.column[kSeparationLimit][k] = curve_.separation_limit(c.column[kRadiusEff][k]);
  }
  // delta_c grows as the cube root of R*, whose largest value is a disk's own
  // radius against a wall.
  double attachment_gap_m(double radius_max_m) const override {
    return radius_max_m > 0 ? curve_.separation_limit(radius_max_m) : 0.0;
  }
  double normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const override {
    const double radius = c.column[kRadiusEff][k];
    if (overlap_m < -c.column[kSeparationLimit][k]) return 0.0;
    const double a = curve_.contact_radius(overlap_m, radius, 0.0);
    return 4.0 * e_eff_pa_ * a * a * a / (3.0 * radius) -
           std::sqrt(8.0 * M_PI * curve_.work_of_adhesion_j_m2 * e_eff_pa_ * a * a * a);
  }

  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    for_disk_pairs(c, b, step, [&](std::size_t k, const Geometry& g) { return force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return apart(c, k, gap); });
  }
  void wall_forces(PairBlock& c, Bodies& b, std::vector<Wall>& walls, const StepContext& step) const override {
    for_wall_pairs(c, b, walls, [&](std::size_t k, const Geometry& g) { return force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return apart(c, k, gap); });
  }

 private:
  // Not yet in contact: apart while there is a gap. In contact: until the curve ends.
  static bool apart(const PairBlock& c, std::size_t k, double gap) {
    const bool formed = c.flags[k] & kTouching;
    if (formed ? gap <= c.column[kSeparationLimit][k] : gap < 0) return false;
    release(c, k);
    return true;
  }

  PairForce force(const PairBlock& c, std::size_t k, const Geometry& g, double dt_s) const {
    const double radius = c.column[kRadiusEff][k];
    NormalForce n;
    const double a = curve_.contact_radius(g.overlap, radius, c.column[kContactRadius][k]);
    n.contact_radius_m = a;
    n.repulsive_n = curve_.repulsive_n(a, radius);
    n.total_n = curve_.total_n(n.repulsive_n, a);
    return hertz_force(c, k, g, dt_s, n);
  }

  JkrCurve curve_;
};

}  // namespace

void register_jkr_model(ContactModelRegistry& registry) {
  registry.add("jkr", hertz_parameter_keys({"work_of_adhesion_j_m2"}), [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<JkrModel>(p, where);
  });
  registry.set_peer_names("jkr", nlohmann::json::parse(R"({
    "liggghts": {"model": "hertz", "notes": ["the wall material (shear_modulus_2_pa, poisson_2) is a second atom type in LIGGGHTS: add its column yourself", "LIGGGHTS-PUBLIC has no JKR: its cohesion sjkr takes a cohesion energy density (J/m^3), not a work of adhesion"],
      "keywords": [{"key": "shear_modulus_pa", "name": "youngsModulus", "as": "youngs_modulus", "with": "poisson"},
                   {"key": "poisson", "name": "poissonsRatio"},
                   {"key": "restitution", "name": "coefficientRestitution", "per": "pair"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"},
                   {"key": "rolling_friction_cdt_relative", "name": "coefficientRollingFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem
