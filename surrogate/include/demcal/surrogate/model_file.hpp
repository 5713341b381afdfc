#pragma once
// Saved models (JSON). Each kind registers a loader under its "kind" string,
// so demcal-predict, sensitivity analysis and inversion load any model the
// same way and a new kind adds one registration, not a switch.
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "demcal/core/model.hpp"

namespace demcal::surrogate {

using ModelLoader = std::function<std::unique_ptr<Model>(const nlohmann::json& file, const std::string& origin)>;

// Registers `loader` for models whose "kind" is `kind`.
void register_model_kind(const std::string& kind, ModelLoader loader);

// Loads a model file; errors name the file and what is wrong (unknown kind,
// missing field).
std::unique_ptr<Model> load_model(const std::string& path);
std::unique_ptr<Model> model_from_json(const nlohmann::json& file, const std::string& origin);

// Writes `file` atomically with a trailing newline.
void save_model(const nlohmann::json& file, const std::string& path);

// The "format" field every model file carries.
inline constexpr const char* kModelFormat = "demcal-model/1";

}  // namespace demcal::surrogate
