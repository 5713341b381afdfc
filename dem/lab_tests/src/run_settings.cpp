#include "demcal/dem/run_settings.hpp"

#include <numeric>

#include "demcal/core/rng.hpp"

namespace demcal::dem {

void apply_run_options(WorldSettings& settings, const RunOptions& options) {
  if (options.threads > 0) settings.threads = options.threads;
  if (options.min_disks_per_thread > 0) settings.min_disks_per_thread = options.min_disks_per_thread;
}

std::vector<std::size_t> particle_order(std::size_t n, std::uint64_t particle_order_seed) {
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (particle_order_seed != 0) {
    Rng rng(particle_order_seed, 0x6f72646572 /* "order" */);
    rng.shuffle(order);
  }
  return order;
}

}  // namespace demcal::dem
