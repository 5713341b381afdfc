#pragma once
// Steps a world in chunks of 500 until `breaks` bonds have broken (or
// `max_steps` have run); returns the steps run. Tests that compare runs load
// a specimen into breakage this way, then run as many steps more.
#include <cstdint>

#include "demcal/dem/world.hpp"

namespace demcal::test {

inline std::uint64_t load_until_breaks(dem::World& world, std::size_t breaks, std::uint64_t max_steps = 200000) {
  std::uint64_t steps = 0;
  while (world.breaks().size() < breaks && steps < max_steps) {
    world.run(500);
    steps += 500;
  }
  return steps;
}

}  // namespace demcal::test
