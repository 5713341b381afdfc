#pragma once
// What a scene has, as the study layer reads it (demcal-dem describe): its
// test, parameters (unit, quantity, default, bounds), outputs (unit,
// description), contact roles and models, and fingerprint.
#include <nlohmann/json.hpp>

#include "demcal/dem/scene.hpp"

namespace demcal::dem {

nlohmann::json describe_scene(const Scene& scene);
// The registered lab tests and contact models.
nlohmann::json describe_registries();

}  // namespace demcal::dem
