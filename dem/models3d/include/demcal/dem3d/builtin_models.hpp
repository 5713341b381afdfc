#pragma once
// The registration function of each built-in 3D contact model (each in its
// own file); ContactModelRegistry::instance() calls them.
namespace demcal::dem3d {

class ContactModelRegistry;

void register_linear_model(ContactModelRegistry& registry);
void register_hertz_mindlin_model(ContactModelRegistry& registry);
void register_jkr_model(ContactModelRegistry& registry);
void register_sjkr_model(ContactModelRegistry& registry);
void register_contact_bond_model(ContactModelRegistry& registry);
void register_parallel_bond_model(ContactModelRegistry& registry);
void register_flat_joint_model(ContactModelRegistry& registry);
void register_builtin_models(ContactModelRegistry& registry);

}  // namespace demcal::dem3d
