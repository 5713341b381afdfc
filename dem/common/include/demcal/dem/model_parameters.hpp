#pragma once
// Reading a contact model's parameters from JSON with one-line errors that
// name where the parameters came from.
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace demcal::dem {

// A finite number.
double number(const nlohmann::json& p, const std::string& key, const std::string& where);
double positive(const nlohmann::json& p, const std::string& key, const std::string& where);
double non_negative(const nlohmann::json& p, const std::string& key, const std::string& where);
// Returns `fallback` when the key is absent.
double non_negative_or(const nlohmann::json& p, const std::string& key, double fallback, const std::string& where);

}  // namespace demcal::dem
