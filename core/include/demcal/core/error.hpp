#pragma once
// The one exception type of demcal. Its message is a single line that names
// the file, field and allowed values, so an executable can print it as is.
#include <stdexcept>
#include <string>

namespace demcal {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace demcal
