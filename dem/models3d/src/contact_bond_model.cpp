// Contact bond in 3D (PFC3D's linearcbond): a linear contact glued at a
// point. While bonded it carries tension and unlimited shear; it breaks when
// the tensile force reaches the normal strength or the shear force's size
// the shear strength, and then slides with Coulomb friction like the linear
// model, from the overlap it was glued at.
//   parameters: the linear model's, and "tensile_strength_pa",
//               "tensile_strength_std_pa" (default 0), "shear_strength_pa",
//               "shear_strength_std_pa" (default 0)
// Strengths are stresses; each bond gets force strengths stress x A with
// A = pi r^2, r = min(R_i, R_j): the area of the linear model's deformability
// method, which PFC3D's `cb_strength` multiplies a stress by. Drawn per bond
// from a normal distribution truncated at zero. A bond installed across a
// small gap or an overlap is force-free there: while bonded,
// F_n = kn (overlap - overlap at installation). Breaking as the 2D model: in
// tension both forces drop to zero; in shear the step's forces stand (unless
// the pair was in tension) and Coulomb's limit applies from the next step.
//   state: the linear columns, then the bond's normal and shear strengths (N).
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/linear_base.hpp"

namespace demcal::dem3d {
namespace {

enum BondColumn : std::size_t {
  kNormalStrength = kLinearColumns,  // N
  kShearStrength,                    // N
};

class ContactBondModel : public LinearBase {
 public:
  ContactBondModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        sigma_c_(dem::non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(dem::non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        tau_c_(dem::non_negative(p, "shear_strength_pa", where)),
        tau_c_std_(dem::non_negative_or(p, "shear_strength_std_pa", 0.0, where)) {}
  std::string name() const override { return "contact_bond"; }
  bool has_bonds() const override { return true; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"bond_normal_strength_n", "bond_shear_strength_n"}) columns.emplace_back(c);
    return columns;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, Rng& rng) const override {
    if (pair.wall) return false;
    const double r = std::min(pair.radius_i, pair.radius_j);
    const double area = M_PI * r * r;
    c.column[kNormalStrength][k] = dem::draw_strength(sigma_c_, sigma_c_std_, rng) * area;
    c.column[kShearStrength][k] = dem::draw_strength(tau_c_, tau_c_std_, rng) * area;
    // Glued as it lies, across a gap too: no force at installation, unless
    // the world kept a locked-in share of an overlap.
    c.column[kReferenceOverlap][k] = std::min(c.column[kReferenceOverlap][k], pair.overlap_m);
    c.flags[k] |= dem::kBonded;
    return true;
  }

  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    for_bondable_pairs(c, s, out, step.dt_s,
                       [&](std::size_t k, const PairContact& p) { bonded(c, k, out, p, step.dt_s); });
  }

  double max_bond_utilisation(const ConstPairBlock& c, const Spheres& s) const override {
    double most = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      if (!(c.flags[k] & dem::kBonded)) continue;
      const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
      const Vec3 d = s.position(j) - s.position(i);
      const double overlap = s.radius[i] + s.radius[j] - std::sqrt(dot(d, d));
      const double fn = c.column[kKn][k] * (overlap - c.column[kReferenceOverlap][k]);
      const Vec3 fs{c.column[kShearX][k], c.column[kShearY][k], c.column[kShearZ][k]};
      most = std::max({most, dem::utilisation(-fn, c.column[kNormalStrength][k]),
                       dem::utilisation(norm(fs), c.column[kShearStrength][k])});
    }
    return most;
  }

 private:
  static void bonded(PairBlock& c, std::size_t k, const PairForces& out, const PairContact& p, double dt_s) {
    const double fn = c.column[kKn][k] * (p.overlap_m - c.column[kReferenceOverlap][k]);  // < 0 in tension
    const Vec3 fs = incremented_shear({c.column[kShearX][k], c.column[kShearY][k], c.column[kShearZ][k]}, p.normal,
                                      p.plane_spin_rad_s, dt_s, p.relative_velocity_m_s, c.column[kKs][k] * dt_s);
    const bool tension = -fn >= c.column[kNormalStrength][k];
    const bool shear = !tension && dot(fs, fs) >= c.column[kShearStrength][k] * c.column[kShearStrength][k];
    const bool released = tension || (shear && fn <= 0);
    dem::PairFlags flags = c.flags[k] & ~static_cast<dem::PairFlags>(dem::kTouching);
    if (tension || shear) flags = mark_break(flags & ~static_cast<dem::PairFlags>(dem::kBonded), tension);
    // Held: touching while the spheres overlap; broken in shear and pressed: touching; released: not.
    if (!released && (shear || p.overlap_m > 0)) flags |= dem::kTouching;
    c.flags[k] = flags;
    if (released) {
      forget_shear(c, k);
      out.set(k, {}, {}, {});
      return;
    }
    c.column[kShearX][k] = fs.x, c.column[kShearY][k] = fs.y, c.column[kShearZ][k] = fs.z;
    set_contact_force(out, k, p, fs - fn * p.normal, fs);
  }

  double sigma_c_, sigma_c_std_, tau_c_, tau_c_std_;
};

}  // namespace

void register_contact_bond_model(ContactModelRegistry& registry) {
  registry.add("contact_bond", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction", "tensile_strength_pa",
                                "tensile_strength_std_pa", "shear_strength_pa", "shear_strength_std_pa"},
               [](const nlohmann::json& p, const std::string& where) {
                 return std::make_unique<ContactBondModel>(p, where);
               });
  // PFC3D's linearcbond takes its strengths after bonding, as stresses it
  // turns into forces with the contact area pi min(R)^2, as this model does.
  registry.set_peer_names("contact_bond", nlohmann::json::parse(R"({
    "pfc": {"model": "linearcbond",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "kn_n_m", "group": "property", "name": "kn"},
                   {"key": "ks_n_m", "group": "property", "name": "ks"},
                   {"key": "friction", "group": "property", "name": "fric"},
                   {"key": "tensile_strength_pa", "group": "cb_strength", "name": "tensile"},
                   {"key": "shear_strength_pa", "group": "cb_strength", "name": "shear"}],
      "later": {"cb_strength": {"command": "contact method cb_strength",
        "text": "after bonding (contact method bond gap ...), the strengths as stresses; PFC3D turns them into the forces cb_tenf and cb_shearf with the contact area pi min(R)^2, as demcal does"}}},
    "yade": {"model": "CohFrictMat", "notes": ["YADE sets its normal stiffness from young as 2 young R1 R2 / (R1 + R2) (PFC3D: pi min(R)^2 E / (R1 + R2)) and its cohesions over its own area: the same numbers make a stiffer or softer material there; check a YADE run against demcal's"],
      "keywords": [{"key": "modulus_pa", "name": "young"}, {"key": "kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "friction", "name": "frictionAngle", "as": "atan"},
                   {"key": "tensile_strength_pa", "name": "normalCohesion"},
                   {"key": "shear_strength_pa", "name": "shearCohesion"}, {"name": "isCohesive", "value": true}]}})"));
}

}  // namespace demcal::dem3d
