#pragma once
// A registry of contact models by name, the same for both engines: each model
// is added with every parameter key a scene may give it and a factory, and
// may declare how other programs name it and its keys (so `export` keeps no
// copy). Each engine holds its own (a 2D and a 3D model may share a name and
// be different laws); the messages name which ("contact model", "3D contact
// model").
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace demcal::dem {

// Everything but the factories: names, keys, peer tables and their checks.
class ModelNames {
 public:
  // `noun`: how messages name a model ("contact model"); `known`: how they
  // introduce the list of known names ("known", "known in 3D").
  ModelNames(std::string noun, std::string known);

  std::vector<std::string> names() const;
  // The keys `name` accepts; throws like find for an unknown model.
  const std::vector<std::string>& parameter_keys(const std::string& name) const;
  // How other programs name the model and its keys: {"pfc"|"yade"|"liggghts":
  // {"model", "keywords": [{"key", "name", ...}], ...}}
  // (docs/reference/executables/demcal-dem.md). Every key a table translates
  // must be one the model takes: a renamed key fails at start-up.
  void set_peer_names(const std::string& name, const nlohmann::json& peer_names);
  // The table of `name` (an empty object when none was set).
  const nlohmann::json& peer_names(const std::string& name) const;

 protected:
  // Adds a name (an Error when it is there already); returns its index.
  std::size_t add_name(const std::string& name, std::vector<std::string> parameter_keys);
  // The index of `name`: an Error "<where>: unknown <noun> ... (<known>: ...)" when there is none.
  std::size_t find(const std::string& name, const std::string& where) const;
  // An Error naming the allowed keys for a key model `index` does not take.
  void check_keys(std::size_t index, const nlohmann::json& parameters, const std::string& where) const;

 private:
  struct Entry {
    std::string name;
    std::vector<std::string> parameter_keys;
    std::shared_ptr<const nlohmann::json> peer_names;  // an empty object until set
  };
  std::string noun_, known_;
  std::vector<Entry> entries_;
};

template <class Model>
class ModelRegistry : public ModelNames {
 public:
  using Factory = std::function<std::unique_ptr<Model>(const nlohmann::json& parameters, const std::string& where)>;
  using ModelNames::ModelNames;

  void add(const std::string& name, std::vector<std::string> parameter_keys, Factory factory) {
    add_name(name, std::move(parameter_keys));
    factories_.push_back(std::move(factory));
  }
  // Throws an Error naming the known models when `name` is unknown, and one
  // naming the allowed keys for a key the model does not take.
  std::unique_ptr<Model> create(const std::string& name, const nlohmann::json& parameters,
                                const std::string& where) const {
    const std::size_t index = find(name, where);
    check_keys(index, parameters, where);
    return factories_[index](parameters, where);
  }

 private:
  std::vector<Factory> factories_;
};

}  // namespace demcal::dem
