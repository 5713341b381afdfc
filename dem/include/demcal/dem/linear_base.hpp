#pragma once
// The linear part every built-in model shares: stiffness by the deformability
// method (E_c, kn/ks), Coulomb friction, and linear contacts with the platens.
// Models derive from it and add their bond.
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/contact_model.hpp"

namespace demcal::dem {

class LinearBase : public ContactModel {
 public:
  // Reads "modulus_pa", "kn_ks" and "friction" from `p`.
  LinearBase(const nlohmann::json& p, const std::string& where);

  void initialise(ContactSet& c, std::size_t k, const PairInfo& pair, double thickness_m) const override;
  // Disk-wall pairs are linear contacts in every built-in model.
  void wall_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b, std::vector<Wall>& walls,
                   const StepContext& step) const override;
  double normal_stiffness_estimate(double radius_m, double thickness_m) const override;

 protected:
  double modulus_pa_, kn_ks_, friction_;
};

}  // namespace demcal::dem
