#pragma once
// The order in which a run's particles enter its world: by how they were
// made, or shuffled (RunOptions::particle_order_seed) by the invariant tests,
// which check that no result depends on it. For either engine.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace demcal::dem {

// 0, 1, ..., n - 1, or shuffled by `particle_order_seed` when it is not 0.
std::vector<std::size_t> particle_order(std::size_t n, std::uint64_t particle_order_seed);

}  // namespace demcal::dem
