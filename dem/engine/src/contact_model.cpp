#include "demcal/dem/contact_model.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"

namespace demcal::dem {

void ContactModel::make_force_free(PairBlock&, std::size_t, double) const {}

double ContactModel::max_bond_utilisation(const ConstPairBlock&, const Bodies&) const { return NAN; }

bool ContactModel::install_bond(PairBlock&, std::size_t, const PairInfo&, double, Rng&) const { return false; }

void ContactModelRegistry::add(const std::string& name, ContactModelFactory factory) {
  for (const auto& entry : factories_)
    if (entry.first == name) throw Error("contact model \"" + name + "\" is registered twice");
  factories_.emplace_back(name, std::move(factory));
}

std::unique_ptr<ContactModel> ContactModelRegistry::create(const std::string& name, const nlohmann::json& parameters,
                                                           const std::string& where) const {
  for (const auto& entry : factories_)
    if (entry.first == name) return entry.second(parameters, where);
  std::string list;
  for (const auto& entry : factories_) list += (list.empty() ? "" : ", ") + entry.first;
  throw Error(where + ": unknown contact model \"" + name + "\" (known: " + list + ")");
}

std::vector<std::string> ContactModelRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& entry : factories_) out.push_back(entry.first);
  return out;
}

}  // namespace demcal::dem
