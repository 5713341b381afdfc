// The linear contact model in 3D (PFC3D's linear model by the deformability
// method): kn = A E* / L with A = pi r^2, r = min(R_i, R_j), L = R_i + R_j
// (a sphere on a wall: r = L = R), ks = kn / (kn/ks), or the springs given
// directly; Coulomb friction; no dashpots.
//   parameters: {"modulus_pa": E*, "kn_ks": kn/ks, "friction": mu} or
//               {"kn_n_m", "ks_n_m", "friction"}
//   state: kn_n_m, ks_n_m, friction, reference_overlap_m, the shear force vector.
#include <nlohmann/json.hpp>

#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/linear_base.hpp"
#include "demcal/dem3d/linear_batch.hpp"

namespace demcal::dem3d {
namespace {

class LinearModel : public LinearBase {
 public:
  using LinearBase::LinearBase;
  std::string name() const override { return "linear"; }
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    // The scalar loop's bits (for_sphere_pairs with linear_touch), vectorised.
    linear_batch::linear_sphere_forces(c, s, out, step);
  }
};

}  // namespace

void register_linear_model(ContactModelRegistry& registry) {
  registry.add("linear", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction"},
               [](const nlohmann::json& p, const std::string& where) { return std::make_unique<LinearModel>(p, where); });
  // PFC3D's linear model by the deformability method (or its kn and ks).
  registry.set_peer_names("linear", nlohmann::json::parse(R"({
    "pfc": {"model": "linear",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "kn_n_m", "group": "property", "name": "kn"},
                   {"key": "ks_n_m", "group": "property", "name": "ks"},
                   {"key": "friction", "group": "property", "name": "fric"}]},
    "yade": {"model": "FrictMat", "notes": ["YADE sets its normal stiffness from young as 2 young R1 R2 / (R1 + R2) (PFC3D: pi min(R)^2 E / (R1 + R2)): check a YADE run against demcal's"],
      "keywords": [{"key": "modulus_pa", "name": "young"}, {"key": "kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "friction", "name": "frictionAngle", "as": "atan"}]}})"));
}

}  // namespace demcal::dem3d
