#include "demcal/dem/model_parameters.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem {

double number(const nlohmann::json& p, const std::string& key, const std::string& where) {
  if (!p.is_object() || !p.contains(key)) throw Error(where + ": missing parameter \"" + key + "\"");
  const auto& v = p.at(key);
  if (!v.is_number()) throw Error(where + ": parameter \"" + key + "\" must be a number");
  double value = v.get<double>();
  if (!std::isfinite(value)) throw Error(where + ": parameter \"" + key + "\" is not finite");
  return value;
}

double positive(const nlohmann::json& p, const std::string& key, const std::string& where) {
  double value = number(p, key, where);
  if (!(value > 0)) throw Error(where + ": " + key + " must be positive (got " + format_double(value) + ")");
  return value;
}

double non_negative(const nlohmann::json& p, const std::string& key, const std::string& where) {
  double value = number(p, key, where);
  if (value < 0) throw Error(where + ": " + key + " must be >= 0 (got " + format_double(value) + ")");
  return value;
}

double non_negative_or(const nlohmann::json& p, const std::string& key, double fallback, const std::string& where) {
  return p.is_object() && p.contains(key) ? non_negative(p, key, where) : fallback;
}

}  // namespace demcal::dem
