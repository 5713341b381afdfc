#include "demcal/dem3d/contact_model.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"

namespace demcal::dem3d {

void ContactModelRegistry::add(const std::string& name, std::vector<std::string> parameter_keys,
                               ContactModelFactory factory) {
  for (const Entry& entry : entries_)
    if (entry.name == name) throw Error("3D contact model \"" + name + "\" is registered twice");
  entries_.push_back({name, std::move(parameter_keys), std::move(factory),
                      std::make_shared<const nlohmann::json>(nlohmann::json::object())});
}

void ContactModelRegistry::set_peer_names(const std::string& name, const nlohmann::json& peer_names) {
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  if (it == entries_.end()) throw Error("3D contact model \"" + name + "\" is not registered");
  // A table may only translate keys the model takes (a renamed key fails at start-up).
  for (const auto& [program, table] : peer_names.items())
    for (const nlohmann::json& keyword : table.value("keywords", nlohmann::json::array()))
      for (const char* field : {"key", "with"}) {
        if (!keyword.contains(field)) continue;
        const std::string key = keyword.at(field).get<std::string>();
        if (std::find(it->parameter_keys.begin(), it->parameter_keys.end(), key) == it->parameter_keys.end())
          throw Error("3D contact model \"" + name + "\": the " + program + " names translate \"" + key +
                      "\", which is not one of its parameters");
      }
  it->peer_names = std::make_shared<const nlohmann::json>(peer_names);
}

const ContactModelRegistry::Entry& ContactModelRegistry::find(const std::string& name, const std::string& where) const {
  for (const Entry& entry : entries_)
    if (entry.name == name) return entry;
  std::string list;
  for (const Entry& entry : entries_) list += (list.empty() ? "" : ", ") + entry.name;
  throw Error(where + ": unknown 3D contact model \"" + name + "\" (known in 3D: " + list + ")");
}

std::unique_ptr<ContactModel> ContactModelRegistry::create(const std::string& name, const nlohmann::json& parameters,
                                                           const std::string& where) const {
  const Entry& entry = find(name, where);
  require_known_fields(parameters, entry.parameter_keys, where, "parameter");
  return entry.factory(parameters, where);
}

std::vector<std::string> ContactModelRegistry::names() const {
  std::vector<std::string> out;
  for (const Entry& entry : entries_) out.push_back(entry.name);
  return out;
}

const std::vector<std::string>& ContactModelRegistry::parameter_keys(const std::string& name) const {
  return find(name, "3D contact model").parameter_keys;
}

const nlohmann::json& ContactModelRegistry::peer_names(const std::string& name) const {
  return *find(name, "3D contact model").peer_names;
}

}  // namespace demcal::dem3d
