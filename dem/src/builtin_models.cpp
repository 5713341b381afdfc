#include "demcal/dem/builtin_models.hpp"

namespace demcal::dem {

void register_builtin_models(ContactModelRegistry& registry) {
  register_linear_model(registry);
  register_parallel_bond_model(registry);
  register_contact_bond_model(registry);
}

}  // namespace demcal::dem
