#include "demcal/dem/particle_order.hpp"

#include <numeric>

#include "demcal/core/rng.hpp"

namespace demcal::dem {

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
