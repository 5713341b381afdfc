#include "demcal/core/rng.hpp"

#include <cmath>

#include "demcal/core/error.hpp"

namespace demcal {

void Rng::seed_engine() {
  std::seed_seq sequence{static_cast<std::uint32_t>(seed_), static_cast<std::uint32_t>(seed_ >> 32),
                         static_cast<std::uint32_t>(stream_), static_cast<std::uint32_t>(stream_ >> 32),
                         0x64656d63u /* "demc" */};
  engine_.emplace(sequence);
}

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

std::uint64_t keyed_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  return splitmix64(splitmix64(splitmix64(seed) ^ a) ^ b);
}

double Rng::uniform() { return static_cast<double>(engine()() >> 11) * 0x1.0p-53; }

double Rng::uniform(double low, double high) { return low + (high - low) * uniform(); }

std::uint64_t Rng::below(std::uint64_t n) {
  if (n == 0) throw Error("Rng::below needs n > 0");
  // Rejection sampling (Lemire's bound) keeps every value equally likely.
  std::uint64_t threshold = (0 - n) % n;
  for (;;) {
    std::uint64_t x = engine()();
    if (x >= threshold) return x % n;
  }
}

double Rng::normal(double mean, double std_dev) {
  // Marsaglia's polar method: two normals per accepted pair.
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return mean + std_dev * spare_normal_;
  }
  double u, v, s;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * factor;
  has_spare_normal_ = true;
  return mean + std_dev * u * factor;
}

double Rng::cauchy() {
  double u;
  do {
    u = uniform();
  } while (u == 0.0 || u == 0.5);
  return std::tan(M_PI * (u - 0.5));
}

}  // namespace demcal
