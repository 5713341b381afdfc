// Contact bond (PFC's linearcbond): a linear contact glued at a point. While
// bonded it carries tension and unlimited shear; it breaks when the tensile
// force reaches the normal strength or the shear force the shear strength,
// and then slides with Coulomb friction like the linear model, from the
// overlap it was glued at (its reference gap stays, as in PFC).
//   parameters: {"modulus_pa", "kn_ks", "friction",
//                "tensile_strength_pa", "tensile_strength_std_pa" (default 0),
//                "shear_strength_pa", "shear_strength_std_pa" (default 0)}
// Strengths are stresses; each bond gets force strengths stress x A with A =
// 2 min(R_i, R_j) t, the contact area of the linear model's deformability
// method, which is what PFC 5+'s `cb_strength` multiplies a stress by to set
// cb_tenf and cb_shearf (before 2026-12-05 here: 2 R_mean t, without a PFC
// source, 9 % stronger on the sandstone); drawn per bond from a normal
// distribution truncated at zero. A bond installed across a small gap (or overlap) is
// force-free there: while bonded, F_n = kn (overlap - overlap at installation).
// Breaking follows PFC's linearcbond: in tension both forces drop to zero; in
// shear the step's forces stand and the Coulomb limit applies from the next
// step.
//   state: the linear columns (whose reference overlap is the overlap at
//   installation, negative across a gap, less any locked-in share), then the
//   bond's normal and shear strengths (forces, N).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/linear_base.hpp"
#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem/pair_batch.hpp"

namespace demcal::dem {
namespace {

enum BondColumn : std::size_t {
  kNormalStrength = kLinearColumns,  // N
  kShearStrength,                    // N
};

class ContactBondModel : public LinearBase {
 public:
  ContactBondModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        sigma_c_(non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        tau_c_(non_negative(p, "shear_strength_pa", where)),
        tau_c_std_(non_negative_or(p, "shear_strength_std_pa", 0.0, where)) {
  }
  std::string name() const override { return "contact_bond"; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"bond_normal_strength_n", "bond_shear_strength_n"}) columns.emplace_back(c);
    return columns;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m, Rng& rng) const override {
    if (pair.wall) return false;
    const double width = 2.0 * std::min(pair.radius_i, pair.radius_j) * thickness_m;  // PFC's contact area
    c.column[kNormalStrength][k] = draw_strength(sigma_c_, sigma_c_std_, rng) * width;
    c.column[kShearStrength][k] = draw_strength(tau_c_, tau_c_std_, rng) * width;
    // Glued as it lies, across a gap too (PFC sets a contact bond's reference
    // gap to its gap): no force at installation, unless the world kept a
    // locked-in share of an overlap (its reference is then below the overlap).
    c.column[kReferenceOverlap][k] = std::min(c.column[kReferenceOverlap][k], pair.overlap);
    c.flags[k] |= kBonded;
    return true;
  }

  // Batches of pairs, each one vectorised loop (pair_batch.hpp): the law's
  // branches as selects, the same arithmetic and bits as pair by pair. A
  // pair neither bonded nor touching is skipped as skip_unbonded_apart skips
  // it: no force, no shear (a broken bond's pair touches until its gap passes
  // the reference gap).
  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    for_pair_batches(c, b, step, [&](std::size_t from, std::size_t n, const GeometryBatch& g, ForceBatch& f) {
      bond_law(c, from, n, g, f, step.dt_s);
    });
  }

  // The break test's tension -F_n and shear |F_s| of each intact bond
  // against its strengths (forces), F_n from the disks' present overlap (the
  // test itself took it before the last move: near enough for a switch).
  double max_bond_utilisation(const ConstPairBlock& c, const Bodies& b) const override {
    double most = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      if (!(c.flags[k] & kBonded)) continue;
      const std::size_t i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
      const double dx = b.x[j] - b.x[i], dy = b.y[j] - b.y[i];
      const double overlap = disk_overlap_m(b.radius[i], b.radius[j], centre_distance_m(dx, dy));
      const PairState<const double> s = c.column.pair(k);
      const double fn = s[kNormalStiffness] * (overlap - s[kReferenceOverlap]);
      most = std::max({most, utilisation(-fn, s[kNormalStrength]), utilisation(std::abs(s[kShearForce]), s[kShearStrength])});
    }
    return most;
  }

 private:
  // Bonded: the normal spring carries tension from the glued overlap and the
  // shear force grows without limit; in tension past the strength both drop
  // to zero (released), past the shear strength the step's forces stand
  // unless the pair was held in tension (then released too). Unbonded: the
  // linear law.
  static void bond_law(const PairBlock& c, std::size_t from, std::size_t n, const GeometryBatch& __restrict g,
                       ForceBatch& __restrict f, double dt) {
    const StateColumns<double> s = c.column.from(from);
    const PairFlags* __restrict flags = c.flags + from;
#pragma omp simd
    for (std::size_t p = 0; p < n; ++p) {
      const bool bonded = (flags[p] & kBonded) != 0;
      const LinearLane lin = linear_lane(s, p, g.overlap[p], g.vs[p], dt);
      const bool skipped = (!bonded) & (!lin.touching);
      const double bond_fn = s(kNormalStiffness, p) * (g.overlap[p] - s(kReferenceOverlap, p));  // negative in tension
      const double bond_fs = s(kShearForce, p) - s(kShearStiffness, p) * g.vs[p] * dt;
      const bool tension = -bond_fn >= s(kNormalStrength, p);
      const bool shear = (!tension) & (std::abs(bond_fs) >= s(kShearStrength, p));
      const bool released = tension | (shear & (bond_fn <= 0));
      const bool broke = bonded & (tension | shear);
      const double fn = select(bonded, select(released, 0.0, bond_fn), lin.fn);
      const double fs = select(bonded, select(released, 0.0, bond_fs), lin.fs);
      s(kShearForce, p) = select(bonded, select(released, 0.0, bond_fs), select(skipped, 0.0, lin.fs));
      batch_force(f, p, g, skipped, fn, fs, 0.0);
      // Bonded and holding: touching while the disks overlap; broken in shear
      // and still pressed: touching; released: not.
      const bool bonded_touching = (!released) & (shear | (g.overlap[p] > 0));
      const bool touching = (bonded & bonded_touching) | ((!bonded) & lin.touching);
      const PairFlags cleared = flags[p] & ~static_cast<PairFlags>(kTouching | (broke ? kBonded : 0u));
      f.flags[p] = cleared | (touching ? static_cast<PairFlags>(kTouching) : 0u);
      f.broke[p] = broke ? 1u : 0u;
      f.tension[p] = tension ? 1u : 0u;
    }
  }

  double sigma_c_, sigma_c_std_, tau_c_, tau_c_std_;
};

}  // namespace

void register_contact_bond_model(ContactModelRegistry& registry) {
  registry.add("contact_bond", {"modulus_pa", "kn_ks", "friction", "tensile_strength_pa", "tensile_strength_std_pa",
                                 "shear_strength_pa", "shear_strength_std_pa"}, [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<ContactBondModel>(p, where);
  });
  // PFC's linearcbond takes its strengths after bonding, as stresses it turns
  // into forces with the contact area 2 min(R) t, as this model does.
  registry.set_peer_names("contact_bond", nlohmann::json::parse(R"({
    "pfc": {"model": "linearcbond",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "friction", "group": "property", "name": "fric"},
                   {"key": "tensile_strength_pa", "group": "cb_strength", "name": "tensile"},
                   {"key": "shear_strength_pa", "group": "cb_strength", "name": "shear"}],
      "later": {"cb_strength": {"command": "contact method cb_strength",
        "text": "after bonding (contact method bond gap ...), the strengths as stresses; PFC turns them into the forces cb_tenf and cb_shearf with the contact area 2 min(R) t, as demcal does"}}},
    "yade": {"model": "CohFrictMat", "notes": [],
      "keywords": [{"key": "modulus_pa", "name": "young"}, {"key": "kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "friction", "name": "frictionAngle", "as": "atan"},
                   {"key": "tensile_strength_pa", "name": "normalCohesion"},
                   {"key": "shear_strength_pa", "name": "shearCohesion"}, {"name": "isCohesive", "value": true}]},
    "liggghts": {"model": "hertz", "notes": ["LIGGGHTS-PUBLIC has no bonds: only the contact's stiffness and friction carry over"],
      "keywords": [{"key": "modulus_pa", "name": "youngsModulus"},
                   {"key": "kn_ks", "name": "poissonsRatio", "as": "hertz_mindlin_poisson"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem
