#include <boost/random/sobol.hpp>

#include <cstdint>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/doe/space_filling.hpp"

namespace demcal::doe {
namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Nested uniform (Owen) scrambling by hashing (Burley 2020): on the
// bit-reversed value, each bit is flipped by a hash of the bits above it.
std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  x = reverse_bits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverse_bits(x);
}

}  // namespace

Design sobol(int runs, int factors, std::uint64_t seed) {
  if (runs < 2) throw Error("sobol: --runs must be at least 2 (got " + std::to_string(runs) + ")");
  if (factors < 1 || factors > 3667) throw Error("sobol: needs 1..3667 factors (got " + std::to_string(factors) + ")");
  using Engine = boost::random::sobol_engine<std::uint32_t, 32u, boost::random::default_sobol_table>;
  Engine engine(static_cast<std::size_t>(factors));
  Rng rng(seed);
  std::vector<std::uint32_t> seeds(static_cast<std::size_t>(factors));
  for (auto& s : seeds) s = static_cast<std::uint32_t>(rng() >> 32);

  Eigen::MatrixXd x(runs, factors);
  for (int i = 0; i < runs; ++i)
    for (int j = 0; j < factors; ++j) {
      // Boost skips the all-zero first point; put it back so 2^m runs form a net.
      std::uint32_t value = i == 0 ? 0u : static_cast<std::uint32_t>(engine());
      std::uint32_t scrambled = owen_scramble(value, seeds[static_cast<std::size_t>(j)]);
      x(i, j) = (static_cast<double>(scrambled) + rng.uniform()) * 0x1.0p-32;
    }
  Design design = make_design("sobol", std::move(x), 0, Coding::Unit);
  bool power_of_two = (runs & (runs - 1)) == 0;
  design.description = "scrambled Sobol (Owen), " + std::to_string(runs) + " runs" +
                       (power_of_two ? "" : " (not a power of two: the stratification of a full net is lost)");
  design.settings["scrambling"] = "owen-hash";
  design.settings["seed"] = std::to_string(seed);
  return design;
}

}  // namespace demcal::doe
