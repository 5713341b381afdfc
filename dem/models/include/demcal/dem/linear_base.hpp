#pragma once
// The linear part every built-in model shares: stiffness by the deformability
// method (E_c, kn/ks) or, in the linear model, set directly (kn, ks per unit
// thickness, PFC's and LAMMPS's gran/hooke form), Coulomb friction, and
// linear contacts with the platens.
// Models derive from it, append their own state columns after its
// kLinearColumns (linear_law.hpp) and add their bond.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/contact_model.hpp"

namespace demcal::dem {

class LinearBase : public ContactModel {
 public:
  // Reads "modulus_pa", "kn_ks" and "friction" from `p`; with
  // `direct_stiffness` "kn_n_m" and "ks_n_m" instead of the first two when
  // `p` has "kn_n_m".
  LinearBase(const nlohmann::json& p, const std::string& where, bool direct_stiffness = false);

  // kn_n_m, ks_n_m, friction, shear_force_n, reference_overlap_m.
  std::vector<std::string> state_columns() const override;
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m) const override;
  // `overlap_m` becomes the pair's reference overlap.
  void make_force_free(PairBlock& c, std::size_t k, double overlap_m) const override;
  // Disk-wall pairs are linear contacts in every built-in model.
  void wall_forces(PairBlock& c, Bodies& b, std::vector<Wall>& walls, const StepContext& step) const override;
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override;
  double normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const override;
  double stiffness_estimate(double radius_m, double thickness_m) const override;

 protected:
  double modulus_pa_ = 0, kn_ks_ = 1, friction_ = 0;
  double kn_n_m_ = 0, ks_n_m_ = 0;  // > 0: the same springs for every pair (no deformability method)
};

}  // namespace demcal::dem
