#pragma once
// What a scene has, as the study layer reads it (demcal-dem describe): its
// test, parameters (unit, quantity, default, bounds), outputs (unit,
// description), contact roles and models, and fingerprint.
#include <nlohmann/json.hpp>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/scene_set.hpp"

namespace demcal::dem {

nlohmann::json describe_scene(const Scene& scene);
// A set of one: describe_scene of its scene. A test list: the same keys
// (parameters: the union; outputs: their names in the set, each with the
// label of its test), with "test": "list", its scenes under "tests" and the
// contacts per label.
nlohmann::json describe_scene_set(const SceneSet& set);
// The registered lab tests and contact models.
nlohmann::json describe_registries();

}  // namespace demcal::dem
