#include "demcal/dem3d/builtin_models.hpp"

#include "demcal/dem3d/contact_model.hpp"

namespace demcal::dem3d {

// The registry lives with the models it holds: the engine declares it and
// never fills it, so it depends on no model.
ContactModelRegistry& ContactModelRegistry::instance() {
  static ContactModelRegistry registry = [] {
    ContactModelRegistry r;
    register_builtin_models(r);
    return r;
  }();
  return registry;
}

void register_builtin_models(ContactModelRegistry& registry) {
  register_linear_model(registry);
  register_hertz_mindlin_model(registry);
  register_jkr_model(registry);
  register_sjkr_model(registry);
  register_contact_bond_model(registry);
  register_parallel_bond_model(registry);
  register_flat_joint_model(registry);
}

}  // namespace demcal::dem3d
