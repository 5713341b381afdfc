#include "demcal/dem/model_registry.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"

namespace demcal::dem {

ModelNames::ModelNames(std::string noun, std::string known) : noun_(std::move(noun)), known_(std::move(known)) {}

std::size_t ModelNames::add_name(const std::string& name, std::vector<std::string> parameter_keys) {
  for (const Entry& entry : entries_)
    if (entry.name == name) throw Error(noun_ + " \"" + name + "\" is registered twice");
  entries_.push_back({name, std::move(parameter_keys), std::make_shared<const nlohmann::json>(nlohmann::json::object())});
  return entries_.size() - 1;
}

std::size_t ModelNames::find(const std::string& name, const std::string& where) const {
  for (std::size_t k = 0; k < entries_.size(); ++k)
    if (entries_[k].name == name) return k;
  std::string list;
  for (const Entry& entry : entries_) list += (list.empty() ? "" : ", ") + entry.name;
  throw Error(where + ": unknown " + noun_ + " \"" + name + "\" (" + known_ + ": " + list + ")");
}

void ModelNames::check_keys(std::size_t index, const nlohmann::json& parameters, const std::string& where) const {
  require_known_fields(parameters, entries_[index].parameter_keys, where, "parameter");
}

std::vector<std::string> ModelNames::names() const {
  std::vector<std::string> out;
  for (const Entry& entry : entries_) out.push_back(entry.name);
  return out;
}

const std::vector<std::string>& ModelNames::parameter_keys(const std::string& name) const {
  return entries_[find(name, noun_)].parameter_keys;
}

void ModelNames::set_peer_names(const std::string& name, const nlohmann::json& peer_names) {
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  if (it == entries_.end()) throw Error(noun_ + " \"" + name + "\" is not registered");
  for (const auto& [program, table] : peer_names.items())
    for (const nlohmann::json& keyword : table.value("keywords", nlohmann::json::array()))
      for (const char* field : {"key", "with"}) {  // a keyword without "key" is a fixed value the program needs
        if (!keyword.contains(field)) continue;
        const std::string key = keyword.at(field).get<std::string>();
        if (std::find(it->parameter_keys.begin(), it->parameter_keys.end(), key) == it->parameter_keys.end())
          throw Error(noun_ + " \"" + name + "\": the " + program + " names translate \"" + key +
                      "\", which is not one of its parameters");
      }
  it->peer_names = std::make_shared<const nlohmann::json>(peer_names);
}

const nlohmann::json& ModelNames::peer_names(const std::string& name) const {
  return *entries_[find(name, noun_)].peer_names;
}

}  // namespace demcal::dem
