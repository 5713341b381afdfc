#include "demcal/dem/linear_base.hpp"

#include <nlohmann/json.hpp>

#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {

LinearBase::LinearBase(const nlohmann::json& p, const std::string& where)
    : modulus_pa_(positive(p, "modulus_pa", where)),
      kn_ks_(positive(p, "kn_ks", where)),
      friction_(non_negative(p, "friction", where)) {}

void LinearBase::initialise(ContactSet& c, std::size_t k, const PairInfo& pair, double thickness_m) const {
  c.kn[k] = deformability_kn(modulus_pa_, pair.radius_i, pair.radius_j, pair.wall, thickness_m);
  c.ks[k] = c.kn[k] / kn_ks_;
  c.mu[k] = friction_;
}

void LinearBase::wall_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b, std::vector<Wall>& walls,
                             const StepContext& step) const {
  for_wall_pairs(c, begin, end, b, walls, [&](std::size_t k, const Geometry& g) { return linear_force(c, k, g, step.dt_s); },
                 [&](std::size_t k, double gap) { return skip_apart(c, k, gap); });
}

double LinearBase::normal_stiffness_estimate(double radius_m, double thickness_m) const {
  return deformability_kn(modulus_pa_, radius_m, radius_m, false, thickness_m);
}

}  // namespace demcal::dem
