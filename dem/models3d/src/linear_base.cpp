#include "demcal/dem3d/linear_base.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem3d {

LinearBase::LinearBase(const nlohmann::json& p, const std::string& where) {
  friction_ = dem::non_negative(p, "friction", where);
  const bool springs = p.contains("kn_n_m") || p.contains("ks_n_m");
  if (springs == (p.contains("modulus_pa") || p.contains("kn_ks")))
    throw Error(where + ": give either modulus_pa and kn_ks (the deformability method) or kn_n_m and ks_n_m");
  if (springs) {
    kn_ = dem::positive(p, "kn_n_m", where), ks_ = dem::non_negative(p, "ks_n_m", where);
  } else {
    modulus_ = dem::positive(p, "modulus_pa", where), kn_ks_ = dem::positive(p, "kn_ks", where);
  }
}

std::vector<std::string> LinearBase::state_columns() const {
  return {"kn_n_m", "ks_n_m", "friction", "reference_overlap_m", "shear_force_x_n", "shear_force_y_n",
          "shear_force_z_n"};
}

double LinearBase::linear_kn(const PairInfo& pair) const {
  if (modulus_ <= 0) return kn_;
  const double r = pair.wall ? pair.radius_i : std::min(pair.radius_i, pair.radius_j);
  const double length = pair.radius_i + pair.radius_j;  // radius_j = 0 for a wall
  return M_PI * r * r * modulus_ / length;
}

void LinearBase::initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const {
  const double kn = linear_kn(pair);
  c.column[kKn][k] = kn;
  c.column[kKs][k] = linear_ks(kn);
  c.column[kFriction][k] = friction_;
}

void LinearBase::make_force_free(PairBlock& c, std::size_t k, double overlap_m) const {
  c.column[kReferenceOverlap][k] = overlap_m;
}

void LinearBase::stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                           double& rotational_nm_rad) const {
  // The stiffer spring bounds translation (kn/ks may be below 1); the shear
  // spring acts at the contact point, `arm_m` from the centre.
  translational_n_m = std::max(c.column[kKn][k], c.column[kKs][k]);
  rotational_nm_rad = c.column[kKs][k] * arm_m * arm_m;
}

double LinearBase::stiffness_estimate(double radius_m) const {
  if (modulus_ <= 0) return std::max(kn_, ks_);
  const double kn = M_PI * radius_m * radius_m * modulus_ / (2 * radius_m);
  return std::max(kn, kn / kn_ks_);
}

}  // namespace demcal::dem3d
