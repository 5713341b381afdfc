// Linear contact model: stiffness by the deformability method, Coulomb friction.
//   parameters: {"modulus_pa": E_c, "kn_ks": kn/ks, "friction": mu}
#include <nlohmann/json.hpp>

#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

class LinearModel : public ContactModel {
 public:
  LinearModel(const nlohmann::json& p, const std::string& where)
      : modulus_pa_(positive(p, "modulus_pa", where)),
        kn_ks_(positive(p, "kn_ks", where)),
        friction_(non_negative(p, "friction", where)) {
    require_only(p, {"modulus_pa", "kn_ks", "friction"}, where);
  }
  std::string name() const override { return "linear"; }

  void initialise(ContactSet& c, std::size_t k, const PairInfo& pair, double thickness_m) const override {
    c.kn[k] = deformability_kn(modulus_pa_, pair.radius_i, pair.radius_j, pair.wall, thickness_m);
    c.ks[k] = c.kn[k] / kn_ks_;
    c.mu[k] = friction_;
  }

  void disk_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b,
                   const StepContext& step) const override {
    for_disk_pairs(c, begin, end, b, [&](std::size_t k, const Geometry& g) { return linear_force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return gap >= 0 ? (release(c, k), true) : false; });
  }

  void wall_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b, std::vector<Wall>& walls,
                   const StepContext& step) const override {
    for_wall_pairs(c, begin, end, b, walls, [&](std::size_t k, const Geometry& g) { return linear_force(c, k, g, step.dt_s); },
                   [&](std::size_t k, double gap) { return gap >= 0 ? (release(c, k), true) : false; });
  }

  double normal_stiffness_estimate(double radius_m, double thickness_m) const override {
    return deformability_kn(modulus_pa_, radius_m, radius_m, false, thickness_m);
  }

 private:
  double modulus_pa_, kn_ks_, friction_;
};

}  // namespace

void register_linear_model(ContactModelRegistry& registry) {
  registry.add("linear", [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<LinearModel>(p, where);
  });
}

}  // namespace demcal::dem
