// Linear contact model: stiffness by the deformability method, Coulomb friction.
//   parameters: {"modulus_pa": E_c, "kn_ks": kn/ks, "friction": mu}
//   state: the linear columns only (kn_n_m, ks_n_m, friction, shear_force_n,
//   reference_overlap_m).
#include <nlohmann/json.hpp>

#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/linear_base.hpp"
#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

class LinearModel : public LinearBase {
 public:
  LinearModel(const nlohmann::json& p, const std::string& where) : LinearBase(p, where, true) {
    require_only(p, {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction"}, where);
  }
  std::string name() const override { return "linear"; }

  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    for_disk_pairs(c, b, step, [&](std::size_t k, const Geometry& g) { return linear_force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return skip_apart(c, k, gap); });
  }
};

}  // namespace

void register_linear_model(ContactModelRegistry& registry) {
  registry.add("linear", [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<LinearModel>(p, where);
  });
}

}  // namespace demcal::dem
