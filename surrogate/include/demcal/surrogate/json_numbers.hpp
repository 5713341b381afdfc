#pragma once
// JSON numbers for statistics: NaN and infinities become null (JSON has no
// such numbers).
#include <cmath>

#include <nlohmann/json.hpp>

namespace demcal::surrogate {

inline nlohmann::json json_number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

}  // namespace demcal::surrogate
