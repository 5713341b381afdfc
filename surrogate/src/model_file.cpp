#include "demcal/surrogate/model_file.hpp"

#include <cmath>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
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

// What every kind must satisfy, whatever its loader read: a finite domain with
// low < high and distinct names, outputs that are distinct and agree with the
// file's "outputs" list, and finite predictions over the domain (a coefficient
// of 1e308 or a scaling range of zero would predict inf or NaN).
void check_model(const Model& model, const nlohmann::json& file, const std::string& origin) {
  std::set<std::string> names;
  for (const InputRange& r : model.domain()) {
    if (!names.insert(r.name).second) throw Error(origin + ": input " + r.name + " is listed twice");
    if (!std::isfinite(r.low) || !std::isfinite(r.high) || !(r.low < r.high) || !std::isfinite(r.high - r.low))
      throw Error(origin + ": input " + r.name + " has the domain [" + format_double(r.low) + ", " +
                  format_double(r.high) + "]; it needs finite low < high");
  }
  std::set<std::string> outputs;
  for (const std::string& o : model.outputs())
    if (!outputs.insert(o).second) throw Error(origin + ": output " + o + " is given twice");
  if (file.contains("outputs")) {
    if (!file["outputs"].is_array()) throw Error(origin + ": \"outputs\" must be a list of names");
    std::vector<std::string> listed;
    for (const auto& o : file["outputs"]) {
      if (!o.is_string()) throw Error(origin + ": \"outputs\" must be a list of names");
      listed.push_back(o.get<std::string>());
    }
    if (listed != model.outputs())
      throw Error(origin + ": \"outputs\" lists other outputs than the model predicts");
  }
  // The centre and the corners of the domain (at most 2^10 of them).
  const std::size_t k = model.domain().size();
  const std::size_t corners = k <= 10 ? (std::size_t{1} << k) : 0;
  std::vector<double> x(k), y(model.outputs().size());
  for (std::size_t c = 0; c <= corners; ++c) {
    for (std::size_t j = 0; j < k; ++j) {
      const InputRange& r = model.domain()[j];
      x[j] = c == corners ? 0.5 * (r.low + r.high) : ((c >> j) & 1 ? r.high : r.low);
    }
    model.predict(x.data(), y.data());
    for (std::size_t o = 0; o < y.size(); ++o)
      if (!std::isfinite(y[o]))
        throw Error(origin + ": the model predicts " + format_double(y[o]) + " for " + model.outputs()[o] +
                    " inside its domain (a coefficient, weight or scaling is out of range)");
  }
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
  if (!file.contains("format") || file["format"] != kModelFormat)
    throw Error(origin + ": \"format\" must be \"" + std::string(kModelFormat) + "\" (a model file of another version)");
  std::unique_ptr<Model> model;
  try {
    model = it->second(file, origin);
  } catch (const nlohmann::json::exception& e) {
    throw Error(origin + ": malformed " + kind + " model (" + e.what() + ")");
  }
  check_model(*model, file, origin);
  return model;
}

std::unique_ptr<Model> load_model(const std::string& path) { return model_from_json(read_json_file(path, "model"), path); }

void save_model(const nlohmann::json& file, const std::string& path) {
  write_file_atomically(path, file.dump(2) + "\n");
}

}  // namespace demcal::surrogate
