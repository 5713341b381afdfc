#include "demcal/dem/contact_model.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"

namespace demcal::dem {

void ContactModel::make_force_free(PairBlock&, std::size_t, double) const {}

double ContactModel::max_bond_utilisation(const ConstPairBlock&, const Bodies&) const { return NAN; }

void ContactModel::add_rolling_limits(const ConstPairBlock&, const Bodies&, bool, double*) const {}

bool ContactModel::install_bond(PairBlock&, std::size_t, const PairInfo&, double, Rng&) const { return false; }

void ContactModelRegistry::add(const std::string& name, std::vector<std::string> parameter_keys,
                               ContactModelFactory factory) {
  for (const Entry& entry : entries_)
    if (entry.name == name) throw Error("contact model \"" + name + "\" is registered twice");
  entries_.push_back({name, std::move(parameter_keys), std::move(factory),
                      std::make_shared<const nlohmann::json>(nlohmann::json::object())});
}

ContactModelRegistry::Entry& ContactModelRegistry::find_mutable(const std::string& name) {
  for (Entry& entry : entries_)
    if (entry.name == name) return entry;
  throw Error("contact model \"" + name + "\" is not registered");
}

void ContactModelRegistry::set_peer_names(const std::string& name, const nlohmann::json& peer_names) {
  Entry& entry = find_mutable(name);
  // Every key a table translates must be one the model takes: a renamed key
  // fails here, at start-up, not as a silently missing line in an export.
  for (const auto& [program, table] : peer_names.items())
    for (const nlohmann::json& keyword : table.value("keywords", nlohmann::json::array())) {
      if (!keyword.contains("key")) continue;  // a fixed value the program needs
      for (const char* field : {"key", "with"}) {
        if (!keyword.contains(field)) continue;
        const std::string key = keyword.at(field).get<std::string>();
        if (std::find(entry.parameter_keys.begin(), entry.parameter_keys.end(), key) == entry.parameter_keys.end())
          throw Error("contact model \"" + name + "\": the " + program + " names translate \"" + key +
                      "\", which is not one of its parameters");
      }
    }
  entry.peer_names = std::make_shared<const nlohmann::json>(peer_names);
}

const nlohmann::json& ContactModelRegistry::peer_names(const std::string& name) const {
  return *find(name, "contact model").peer_names;
}

const ContactModelRegistry::Entry& ContactModelRegistry::find(const std::string& name, const std::string& where) const {
  for (const Entry& entry : entries_)
    if (entry.name == name) return entry;
  std::string list;
  for (const Entry& entry : entries_) list += (list.empty() ? "" : ", ") + entry.name;
  throw Error(where + ": unknown contact model \"" + name + "\" (known: " + list + ")");
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
  return find(name, "contact model").parameter_keys;
}

}  // namespace demcal::dem
