#include "demcal/surrogate/model_file.hpp"

#include <map>

#include <nlohmann/json.hpp>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/surrogate/neural_network_model.hpp"
#include "demcal/surrogate/response_surface_model.hpp"

namespace demcal::surrogate {

namespace {

std::map<std::string, ModelLoader>& registry() {
  static std::map<std::string, ModelLoader> loaders;
  return loaders;
}

// The built-in kinds, registered on first use (static libraries drop unused
// self-registering objects, so registration is explicit).
void register_builtin_kinds() {
  static bool done = false;
  if (done) return;
  done = true;
  register_response_surface_kinds();
  register_neural_network_kind();
}

}  // namespace

void register_model_kind(const std::string& kind, ModelLoader loader) { registry()[kind] = std::move(loader); }

std::unique_ptr<Model> model_from_json(const nlohmann::json& file, const std::string& origin) {
  register_builtin_kinds();
  if (!file.is_object() || !file.contains("kind") || !file["kind"].is_string())
    throw Error(origin + ": not a demcal model (no \"kind\" field)");
  std::string kind = file["kind"].get<std::string>();
  auto it = registry().find(kind);
  if (it == registry().end()) {
    std::string list;
    for (const auto& entry : registry()) list += (list.empty() ? "" : ", ") + entry.first;
    throw Error(origin + ": unknown model kind \"" + kind + "\" (known: " + list + ")");
  }
  try {
    return it->second(file, origin);
  } catch (const nlohmann::json::exception& e) {
    throw Error(origin + ": malformed " + kind + " model (" + e.what() + ")");
  }
}

std::unique_ptr<Model> load_model(const std::string& path) { return model_from_json(read_json_file(path, "model"), path); }

void save_model(const nlohmann::json& file, const std::string& path) {
  write_file_atomically(path, file.dump(2) + "\n");
}

}  // namespace demcal::surrogate
