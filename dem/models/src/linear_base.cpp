#include "demcal/dem/linear_base.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {

LinearBase::LinearBase(const nlohmann::json& p, const std::string& where, bool direct_stiffness)
    : friction_(non_negative(p, "friction", where)) {
  if (direct_stiffness && p.contains("kn_n_m")) {
    if (p.contains("modulus_pa") || p.contains("kn_ks"))
      throw Error(where + ": give either kn_n_m and ks_n_m or modulus_pa and kn_ks, not both");
    kn_n_m_ = positive(p, "kn_n_m", where);
    ks_n_m_ = positive(p, "ks_n_m", where);
    kn_ks_ = kn_n_m_ / ks_n_m_;
    return;
  }
  if (direct_stiffness && p.contains("ks_n_m"))
    throw Error(where + ": ks_n_m goes with kn_n_m (give both, or modulus_pa and kn_ks)");
  modulus_pa_ = positive(p, "modulus_pa", where);
  kn_ks_ = positive(p, "kn_ks", where);
}

std::vector<std::string> LinearBase::state_columns() const {
  return {"kn_n_m", "ks_n_m", "friction", "shear_force_n", "reference_overlap_m"};
}

void LinearBase::initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m) const {
  if (kn_n_m_ > 0) {
    c.column[kNormalStiffness][k] = kn_n_m_;
    c.column[kShearStiffness][k] = ks_n_m_;
  } else {
    const double kn = deformability_kn(modulus_pa_, pair.radius_i, pair.radius_j, pair.wall, thickness_m);
    c.column[kNormalStiffness][k] = kn;
    c.column[kShearStiffness][k] = kn / kn_ks_;
  }
  c.column[kFriction][k] = friction_;
  c.column[kReferenceOverlap][k] = 0.0;
}

void LinearBase::make_force_free(PairBlock& c, std::size_t k, double overlap_m) const {
  c.column[kReferenceOverlap][k] = overlap_m;
}

void LinearBase::wall_forces(PairBlock& c, Bodies& b, std::vector<Wall>& walls, const StepContext& step) const {
  for_wall_pairs(c, b, walls, [&](std::size_t k, const Geometry& g) { return linear_force(c, k, g, step.dt_s); },
                 [&](std::size_t k, double gap) { return skip_apart(c, k, gap); });
}

void LinearBase::stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                           double& rotational_nm_rad) const {
  // The stiffer of the two springs bounds translation (kn/ks may be below 1);
  // the shear spring acts at the contact point, `arm_m` from the centre.
  translational_n_m = std::max(c.column[kNormalStiffness][k], c.column[kShearStiffness][k]);
  rotational_nm_rad = c.column[kShearStiffness][k] * arm_m * arm_m;
}

double LinearBase::normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const {
  return c.column[kNormalStiffness][k] * std::max(0.0, overlap_m - c.column[kReferenceOverlap][k]);
}

double LinearBase::stiffness_estimate(double radius_m, double thickness_m) const {
  if (kn_n_m_ > 0) return std::max(kn_n_m_, ks_n_m_);
  return deformability_kn(modulus_pa_, radius_m, radius_m, false, thickness_m) * std::max(1.0, 1.0 / kn_ks_);
}

}  // namespace demcal::dem
