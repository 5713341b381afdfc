#pragma once
// One registration function per built-in contact model (each in its own file).
#include "demcal/dem/contact_model.hpp"

namespace demcal::dem {

void register_linear_model(ContactModelRegistry& registry);
void register_parallel_bond_model(ContactModelRegistry& registry);
void register_contact_bond_model(ContactModelRegistry& registry);
void register_flat_joint_model(ContactModelRegistry& registry);
void register_hertz_mindlin_model(ContactModelRegistry& registry);
void register_jkr_model(ContactModelRegistry& registry);

// Calls every registration above; ContactModelRegistry::instance() runs it once.
void register_builtin_models(ContactModelRegistry& registry);

}  // namespace demcal::dem
