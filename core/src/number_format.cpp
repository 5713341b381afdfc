#include "demcal/core/number_format.hpp"

#include "demcal/core/error.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace demcal {

std::string format_double(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

bool parse_double(std::string_view text, double& value) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
    text.remove_suffix(1);
  if (text.empty()) {
    value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  if (text.front() == '+') text.remove_prefix(1);
  auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

}  // namespace demcal

namespace demcal {

std::pair<std::string, double> parse_name_value(const std::string& text, const std::string& option) {
  const std::size_t eq = text.find('=');
  double value = 0;
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size() || !parse_double(text.substr(eq + 1), value))
    throw Error(option + " \"" + text + "\": expected NAME=VALUE with a number");
  return {text.substr(0, eq), value};
}

}  // namespace demcal
