// JKR cohesion on the 3D Hertz-Mindlin family (hertz_base.hpp), the 2D
// model's law and keys: the curve of demcal/dem/jkr_curve.hpp for the work of
// adhesion w (J/m^2), pull-off -1.5 pi w R*. (A code that writes the same law
// with a surface energy gamma = w / 2 has pull-off 3 pi gamma R*; EDEM's
// documented 1.5 pi gamma R* makes its gamma our w: convert with care.)
// Hysteresis: a pair's contact forms when the spheres touch (overlap > 0) and
// holds, pulling, until the separation at which the curve ends, delta_c;
// friction and rolling resistance use the repulsive part 4 E* a^3 / (3 R*).
// The neighbour list's skin must exceed delta_c for the largest pair: the
// model states it (attachment_gap_m) and the world checks.
//   parameters: the family's and "work_of_adhesion_j_m2" (w >= 0).
//   state: the family's, then delta_c.
#include <nlohmann/json.hpp>

#include "demcal/dem/jkr_curve.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/hertz_base.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::size_t kSeparationLimit = kHertzColumns;  // delta_c, m

class JkrModel : public HertzBase {
 public:
  JkrModel(const nlohmann::json& p, const std::string& where)
      : HertzBase(p, where), curve_(e_eff_pa_, dem::non_negative(p, "work_of_adhesion_j_m2", where)) {}
  std::string name() const override { return "jkr"; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = HertzBase::state_columns();
    columns.push_back("separation_limit_m");
    return columns;
  }
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const override {
    HertzBase::initialise(c, k, pair);
    c.column[kSeparationLimit][k] = curve_.separation_limit(c.column[kRadiusEff][k]);
  }
  // delta_c grows as the cube root of R*, largest for a sphere against a wall.
  double attachment_gap_m(double radius_max_m) const override {
    return radius_max_m > 0 ? curve_.separation_limit(radius_max_m) : 0.0;
  }

  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    PairContact p;
    for (std::size_t k = 0; k < c.size; ++k) {
      const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
      sphere_pair_geometry(s, i, j, p);
      if (in_contact(c, k, p.overlap_m))
        hertz_touch(c, k, out, p, step.dt_s, normal(c, k, p), s.spin(i), s.spin(j));
      else
        release(c, k, out);
    }
  }
  void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                   const StepContext& step) const override {
    PairContact p;
    for (std::size_t k = 0; k < c.size; ++k) {
      const auto i = static_cast<std::size_t>(c.i[k]);
      wall_pair_geometry(s, i, g, k, p);
      if (in_contact(c, k, p.overlap_m))
        hertz_touch(c, k, out, p, step.dt_s, normal(c, k, p), s.spin(i), {});
      else
        release(c, k, out);
    }
  }

 private:
  // Not yet in contact: while the spheres overlap. In contact: until the curve ends.
  static bool in_contact(const PairBlock& c, std::size_t k, double overlap_m) {
    const bool formed = c.flags[k] & dem::kTouching;
    return formed ? overlap_m >= -c.column[kSeparationLimit][k] : overlap_m > 0;
  }
  NormalForce normal(const PairBlock& c, std::size_t k, const PairContact& p) const {
    const double radius = c.column[kRadiusEff][k];
    NormalForce f;
    f.contact_radius_m = curve_.contact_radius(p.overlap_m, radius, c.column[kContactRadius][k]);
    f.repulsive_n = curve_.repulsive_n(f.contact_radius_m, radius);
    f.total_n = curve_.total_n(f.repulsive_n, f.contact_radius_m);
    return f;
  }

  dem::JkrCurve curve_;
};

}  // namespace

void register_jkr_model(ContactModelRegistry& registry) {
  registry.add("jkr", hertz_parameter_keys({"work_of_adhesion_j_m2"}),
               [](const nlohmann::json& p, const std::string& where) { return std::make_unique<JkrModel>(p, where); });
}

}  // namespace demcal::dem3d
