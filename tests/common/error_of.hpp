#pragma once
// The message of the demcal::Error that `f` throws, or "" when it throws none:
// tests assert on what the user would read.
#include <string>

#include "demcal/core/error.hpp"

namespace demcal::test {

template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const demcal::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace demcal::test
