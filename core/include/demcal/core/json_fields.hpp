#pragma once
// Rejects unknown fields of a JSON object, so a typo in a space, scene or
// model file is an error that names it instead of a silently ignored value.
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace demcal {

// Throws "<where>: unknown <noun> "<key>" (allowed: a, b, c)" for the first
// key of `object` not in `allowed`, and "<where>: must be a JSON object" when
// it is not an object.
void require_known_fields(const nlohmann::json& object, std::initializer_list<const char*> allowed,
                          const std::string& where, const char* noun = "field");
// The same for a list built at run time (a lab test's own scene sections).
void require_known_fields(const nlohmann::json& object, const std::vector<std::string>& allowed,
                          const std::string& where, const char* noun = "field");

// A number field of `object` (`fallback` when absent); an Error
// "<where>: "<key>" must be a finite number" otherwise.
double number_field(const nlohmann::json& object, const char* key, double fallback, const std::string& where);
// A string field that must be one of `choices`: its index (`fallback` when
// absent); an Error naming the allowed values otherwise.
std::size_t choice_field(const nlohmann::json& object, const char* key, const std::vector<std::string>& choices,
                         std::size_t fallback, const std::string& where);

// Reads a whole JSON file; errors say "<path>: cannot open <what>" or
// "<path>: not valid JSON (...)".
nlohmann::json read_json_file(const std::string& path, const std::string& what);

}  // namespace demcal
