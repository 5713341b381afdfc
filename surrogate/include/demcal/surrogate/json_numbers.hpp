#pragma once
// JSON numbers for statistics: NaN and infinities become null (JSON has no
// such numbers), and reading back turns null into NaN.
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

namespace demcal::surrogate {

inline nlohmann::json json_number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

inline double number_from_json(const nlohmann::json& value) {
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  return value.get<double>();
}

}  // namespace demcal::surrogate
