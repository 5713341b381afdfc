#include "demcal/core/wall_timeout.hpp"

namespace demcal {

namespace {
const std::string kPrefix = "timeout: ";
}

std::string wall_timeout_reason(const std::string& what) { return kPrefix + what; }

bool is_wall_timeout(const std::string& reason) { return reason.compare(0, kPrefix.size(), kPrefix) == 0; }

}  // namespace demcal
