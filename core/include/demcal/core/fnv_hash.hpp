#pragma once
// FNV-1a, 64 bit: the fingerprints of scenes and test lists (stable across
// platforms and runs, which std::hash is not).
#include <cstdint>
#include <string>

namespace demcal {

inline std::uint64_t fnv1a_64(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace demcal
