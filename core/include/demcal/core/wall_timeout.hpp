#pragma once
// A run stopped by a wall-clock limit (a test's max_wall_s, an external
// command's timeout_s). The machine's load decided it, not the physics, so a
// resumed batch runs such a point again rather than keeping it as failed.
#include <string>

namespace demcal {

// The failure's reason: "timeout: " + what happened.
std::string wall_timeout_reason(const std::string& what);

// Whether a failure's reason is one wall_timeout_reason() wrote.
bool is_wall_timeout(const std::string& reason);

}  // namespace demcal
