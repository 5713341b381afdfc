#pragma once
// A run's options that reach the world it builds: its threads and the order
// in which its particles enter (RunOptions; results must not depend on them).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "demcal/dem/test_result.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

// Sets the world's threads and disks per thread from the options where they are given.
void apply_run_options(WorldSettings& settings, const RunOptions& options);

// The order in which `n` particles enter the world: 0, 1, ..., n - 1, or
// shuffled by `particle_order_seed` when it is not 0.
std::vector<std::size_t> particle_order(std::size_t n, std::uint64_t particle_order_seed);

}  // namespace demcal::dem
