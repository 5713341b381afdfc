// Parallel bond (Potyondy & Cundall 2004) in parallel with a linear contact.
//   parameters: {"modulus_pa", "kn_ks", "friction"                (linear part)
//                "bond_modulus_pa", "bond_kn_ks", "radius_multiplier" (lambda, default 1),
//                "tensile_strength_pa", "tensile_strength_std_pa" (default 0),
//                "shear_strength_pa", "shear_strength_std_pa"     (default 0)}
// Bond: R_b = lambda min(R_i, R_j), A = 2 R_b t, I = 2/3 R_b^3 t,
// kn_b = E_b / (R_i + R_j), ks_b = kn_b / (kn/ks)_b; forces and moment grow
// incrementally; it breaks in tension when -F_n/A + |M| R_b / I >= sigma_c,
// else in shear when |F_s| / A >= tau_c.
//   state: the linear columns, then the bond's stiffness per area, geometry,
//   force, shear force, moment and the strengths drawn for it.
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
  kBondKn = kLinearColumns,  // normal stiffness per area, Pa/m
  kBondKs,                   // shear stiffness per area, Pa/m
  kBondArea,                 // m^2
  kBondInertia,              // m^4
  kBondRadius,               // m
  kBondFn,                   // normal force (compression > 0), N
  kBondFs,                   // shear force, N
  kBondM,                    // moment, N m
  kTensileStrength,          // Pa
  kShearStrength,            // Pa
};

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
  }
  std::string name() const override { return "parallel_bond"; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"bond_kn_pa_m", "bond_ks_pa_m", "bond_area_m2", "bond_inertia_m4", "bond_radius_m",
                          "bond_normal_force_n", "bond_shear_force_n", "bond_moment_nm", "bond_tensile_strength_pa",
                          "bond_shear_strength_pa"})
      columns.emplace_back(c);
    return columns;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m, Rng& rng) const override {
    if (pair.wall) return false;
    const double rb = lambda_ * std::min(pair.radius_i, pair.radius_j);
    c.column[kBondRadius][k] = rb;
    c.column[kBondArea][k] = 2.0 * rb * thickness_m;
    c.column[kBondInertia][k] = 2.0 / 3.0 * rb * rb * rb * thickness_m;
    c.column[kBondKn][k] = bond_modulus_pa_ / (pair.radius_i + pair.radius_j);
    c.column[kBondKs][k] = c.column[kBondKn][k] / bond_kn_ks_;
    c.column[kBondFn][k] = c.column[kBondFs][k] = c.column[kBondM][k] = 0.0;
    c.column[kTensileStrength][k] = draw_strength(sigma_c_, sigma_c_std_, rng);
    c.column[kShearStrength][k] = draw_strength(tau_c_, tau_c_std_, rng);
    c.flags[k] |= kBonded;
    return true;
  }

  // The linear contact and the bond over batches of pairs, each batch one
  // branch-free vectorised loop (pair_batch.hpp): the same arithmetic as the
  // pair-by-pair form below it in the history (for_disk_pairs with the linear
  // law and the bond's update), the same bits. A pair neither bonded nor
  // touching is skipped as skip_unbonded_apart skips it: no force, no shear.
  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    for_pair_batches(c, b, step, [&](std::size_t from, std::size_t n, const GeometryBatch& g, ForceBatch& f) {
      bond_law(c, from, n, g, f, step.dt_s);
    });
  }

  // The bond adds its springs in parallel with the contact's (kept after a
  // break, as a bound on the step): translation by the stiffer of the normal
  // and shear sums, rotation by the shear sum at the contact point plus the
  // bond's bending stiffness (tests/dem/test_time_step.cpp checks both against
  // the eigenfrequencies of bonded clusters).
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    const double area = c.column[kBondArea][k];
    const double normal = c.column[kNormalStiffness][k] + c.column[kBondKn][k] * area;
    const double shear = c.column[kShearStiffness][k] + c.column[kBondKs][k] * area;
    translational_n_m = std::max(normal, shear);
    rotational_nm_rad = shear * arm_m * arm_m + c.column[kBondKn][k] * c.column[kBondInertia][k];
  }

  // The break test's sigma = -F_n / A + |M| R_b / I and tau = |F_s| / A of
  // each intact bond against its strengths.
  double max_bond_utilisation(const ConstPairBlock& c, const Bodies&) const override {
    double most = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      if (!(c.flags[k] & kBonded)) continue;
      const PairState<const double> s = c.column.pair(k);
      const double sigma = -s[kBondFn] / s[kBondArea] + std::abs(s[kBondM]) * s[kBondRadius] / s[kBondInertia];
      const double tau = std::abs(s[kBondFs]) / s[kBondArea];
      most = std::max({most, utilisation(sigma, s[kTensileStrength]), utilisation(tau, s[kShearStrength])});
    }
    return most;
  }

  double stiffness_estimate(double radius_m, double thickness_m) const override {
    const double rb = lambda_ * radius_m;
    const double bond_kn = bond_modulus_pa_ / (2.0 * radius_m) * 2.0 * rb * thickness_m;
    return LinearBase::stiffness_estimate(radius_m, thickness_m) + bond_kn * std::max(1.0, 1.0 / bond_kn_ks_);
  }

 private:
  // Pairs [from, from + n) of the block: their state updated, their forces and
  // flags into `f`. Every condition is a select, so the loop vectorises.
  static void bond_law(const PairBlock& c, std::size_t from, std::size_t n, const GeometryBatch& __restrict g,
                       ForceBatch& __restrict f, double dt) {
    const StateColumns<double> s = c.column.from(from);
    const PairFlags* __restrict flags = c.flags + from;
#pragma omp simd
    for (std::size_t p = 0; p < n; ++p) {
      const LinearLane lin = linear_lane(s, p, g.overlap[p], g.vs[p], dt);
      const double fn = lin.fn, fs = lin.fs;
      const bool touching = lin.touching;
      const bool bonded = (flags[p] & kBonded) != 0;
      const bool skipped = (!bonded) & (!touching);
      s(kShearForce, p) = select(skipped, 0.0, fs);
      // The bond's increments and its strength test (sigma and tau times A I
      // and A: no division).
      const double area = s(kBondArea, p), inertia = s(kBondInertia, p);
      const double bond_fn = s(kBondFn, p) - s(kBondKn, p) * area * g.vn[p] * dt;
      const double bond_fs = s(kBondFs, p) - s(kBondKs, p) * area * g.vs[p] * dt;
      const double bond_m = s(kBondM, p) - s(kBondKn, p) * inertia * g.relative_w[p] * dt;
      const double sigma_ai = -bond_fn * inertia + std::abs(bond_m) * s(kBondRadius, p) * area;
      const double tau_a = std::abs(bond_fs);
      const bool tension = sigma_ai >= s(kTensileStrength, p) * area * inertia;
      const bool broke = bonded & (tension | (tau_a >= s(kShearStrength, p) * area));
      const bool intact = bonded & (!broke);
      s(kBondFn, p) = select(intact, bond_fn, select(broke, 0.0, s(kBondFn, p)));
      s(kBondFs, p) = select(intact, bond_fs, select(broke, 0.0, s(kBondFs, p)));
      s(kBondM, p) = select(intact, bond_m, select(broke, 0.0, s(kBondM, p)));
      const double fn_total = select(intact, fn + bond_fn, fn);
      const double fs_total = select(intact, fs + bond_fs, fs);
      const double moment = select(intact, bond_m, 0.0);
      batch_force(f, p, g, skipped, fn_total, fs_total, moment);
      const PairFlags cleared = flags[p] & ~static_cast<PairFlags>(kTouching | (broke ? kBonded : 0u));
      f.flags[p] = cleared | (touching ? static_cast<PairFlags>(kTouching) : 0u);
      f.broke[p] = broke ? 1u : 0u;
      f.tension[p] = tension ? 1u : 0u;
    }
  }

  double bond_modulus_pa_, bond_kn_ks_, lambda_;
  double sigma_c_, sigma_c_std_, tau_c_, tau_c_std_;
};

}  // namespace

void register_parallel_bond_model(ContactModelRegistry& registry) {
  registry.add("parallel_bond", {"modulus_pa", "kn_ks", "friction", "bond_modulus_pa", "bond_kn_ks",
                                  "radius_multiplier", "tensile_strength_pa", "tensile_strength_std_pa",
                                  "shear_strength_pa", "shear_strength_std_pa"}, [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<ParallelBondModel>(p, where);
  });
  // PFC's linearpbond (pb_fa 0: this bond has no friction angle); YADE's
  // nearest is a cohesive-frictional contact without the bond's own stiffness.
  registry.set_peer_names("parallel_bond", nlohmann::json::parse(R"({
    "pfc": {"model": "linearpbond",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "bond_modulus_pa", "group": "pb_deformability", "name": "emod"},
                   {"key": "bond_kn_ks", "group": "pb_deformability", "name": "kratio"},
                   {"key": "friction", "group": "property", "name": "fric"},
                   {"key": "tensile_strength_pa", "group": "property", "name": "pb_ten"},
                   {"key": "shear_strength_pa", "group": "property", "name": "pb_coh"},
                   {"group": "property", "name": "pb_fa", "value": 0},
                   {"key": "radius_multiplier", "group": "property", "name": "pb_rmul", "default": 1}]},
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
