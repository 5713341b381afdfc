#pragma once
// What the scene layer needs of an engine's contact models, whatever the
// dimension: their names, the keys each takes, how other programs name them,
// and a check of a bound parameter set. Each lab test answers with its own
// engine's catalog (LabTest::contact_models), so a 3D model named in a 2D
// scene, or the reverse, is refused when the scene loads.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace demcal::dem {

class ContactModelCatalog {
 public:
  virtual ~ContactModelCatalog() = default;
  // "2d" or "3d": the engine the models run in (describe --registries groups by it).
  virtual std::string dimension() const = 0;
  virtual std::vector<std::string> names() const = 0;
  // Throws an Error naming the known models for an unknown `model`.
  virtual const std::vector<std::string>& parameter_keys(const std::string& model) const = 0;
  virtual const nlohmann::json& peer_names(const std::string& model) const = 0;
  // Builds the model from `bound` (numbers) and discards it: an Error naming
  // `where` and the key for an unknown model, key or bad value.
  virtual void check(const std::string& model, const nlohmann::json& bound, const std::string& where) const = 0;
};

// The catalog of a test without contact models of ours (an external command's).
const ContactModelCatalog& no_contact_models();

// An engine's model registry (dem/common's ModelRegistry: its instance(),
// names, parameter_keys, peer_names and create) as a catalog: each engine
// instantiates it with its own registry, so this layer names no engine.
template <class Registry>
class RegistryCatalog : public ContactModelCatalog {
 public:
  explicit RegistryCatalog(std::string dimension) : dimension_(std::move(dimension)) {}
  std::string dimension() const override { return dimension_; }
  std::vector<std::string> names() const override { return Registry::instance().names(); }
  const std::vector<std::string>& parameter_keys(const std::string& model) const override {
    return Registry::instance().parameter_keys(model);
  }
  const nlohmann::json& peer_names(const std::string& model) const override {
    return Registry::instance().peer_names(model);
  }
  void check(const std::string& model, const nlohmann::json& bound, const std::string& where) const override {
    Registry::instance().create(model, bound, where);
  }

 private:
  std::string dimension_;
};

}  // namespace demcal::dem
