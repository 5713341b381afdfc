#pragma once
// Seeded random numbers. Every random thing in demcal takes a seed and draws
// from an Rng, so the same inputs and seed give the same numbers. Uniform
// doubles, integers and shuffles are computed here rather than by the standard
// library's distributions, whose algorithms differ between implementations.
#include <cstdint>
#include <optional>
#include <random>
#include <utility>
#include <vector>

namespace demcal {

class Rng {
 public:
  using result_type = std::uint64_t;

  // `stream` separates independent streams of one seed (e.g. one per design
  // point or per restart) without them overlapping in practice. The engine
  // is seeded at the first draw: seeding costs far more than a draw, and a
  // bond whose strengths have no scatter takes an Rng it never uses.
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0) : seed_(seed), stream_(stream) {}

  static constexpr result_type min() { return std::mt19937_64::min(); }
  static constexpr result_type max() { return std::mt19937_64::max(); }
  result_type operator()() { return engine()(); }

  double uniform();                        // [0, 1) with 53 random bits
  double uniform(double low, double high);  // [low, high)
  std::uint64_t below(std::uint64_t n);     // unbiased integer in [0, n)
  double normal(double mean, double std_dev);
  double cauchy();                          // standard Cauchy

  template <typename T>
  void shuffle(std::vector<T>& values) {
    for (std::size_t i = values.size(); i > 1; --i) std::swap(values[i - 1], values[below(i)]);
  }

 private:
  std::mt19937_64& engine() {
    if (!engine_) seed_engine();
    return *engine_;
  }
  void seed_engine();

  std::uint64_t seed_, stream_;
  std::optional<std::mt19937_64> engine_;  // empty until the first draw
  bool has_spare_normal_ = false;
  double spare_normal_ = 0.0;
};

// A seed for draws keyed by identity rather than by the order they are made
// in (e.g. a bond's strength from the seed and the stable ids of its two
// particles): splitmix64 over the three words, so neighbouring keys give
// unrelated seeds. Sorting particles or running threads cannot change it.
std::uint64_t keyed_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b);

}  // namespace demcal
