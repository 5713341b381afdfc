#pragma once
// A run's options that reach the world it builds: its threads and the order
// in which its particles enter (RunOptions; results must not depend on them).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "demcal/dem/particle_order.hpp"
#include "demcal/dem/test_result.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

// Sets the world's threads and disks per thread from the options where they are given.
void apply_run_options(WorldSettings& settings, const RunOptions& options);

}  // namespace demcal::dem
