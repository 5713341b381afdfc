// A chain of disks joined by parallel bonds is a mass-spring chain: a long
// pulse travels at c = L sqrt(k / m), and without damping the integrator
// conserves the chain's (leapfrog) energy to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/core/rng.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "bonded_bodies.hpp"

using namespace demcal::dem;

namespace {

constexpr double kRadius = 1e-3, kGap = 1e-7, kDensity = 2650, kBondModulus = 5e9;

World chain(int n) { return demcal::dem::testing::bonded_chain(n, kRadius, kGap, kDensity, kBondModulus); }

// Time of the largest value of `history`, refined by a parabola through the peak.
double peak_time(const std::vector<double>& history, double dt) {
  std::size_t k = 1;
  for (std::size_t s = 1; s + 1 < history.size(); ++s)
    if (history[s] > history[k]) k = s;
  double a = history[k - 1], b = history[k], c = history[k + 1];
  return (static_cast<double>(k) + 0.5 * (a - c) / (a - 2 * b + c)) * dt;
}

}  // namespace

TEST(BondedChain, LongPulseTravelsAtLSqrtKOverM) {
  const int n = 600;
  World world = chain(n);
  const double spacing = 2 * kRadius + kGap;
  const double k = kBondModulus * 1.0;  // kn_b A = E_b / (2R) * 2R t
  const double m = kDensity * M_PI * kRadius * kRadius;
  const double c = spacing * std::sqrt(k / m);
  // Gaussian velocity pulse 15 spacings wide: wavelengths >> spacing, little dispersion.
  for (int i = 0; i < n; ++i) world.bodies.vx[i] = 1e-3 * std::exp(-std::pow((i - 150) / 15.0, 2));
  const int monitor_a = 300, monitor_b = 500;
  std::vector<double> at_a, at_b;
  const double travel_time = (monitor_b - 150 + 60) * spacing / c;
  world.step();
  const double dt = world.dt_s();
  while (world.time_s() < travel_time) {
    at_a.push_back(world.bodies.vx[monitor_a]);
    at_b.push_back(world.bodies.vx[monitor_b]);
    world.step();
  }
  const double lag = peak_time(at_b, dt) - peak_time(at_a, dt);
  const double measured = (monitor_b - monitor_a) * spacing / lag;
  EXPECT_NEAR(measured, c, 0.01 * c);
}

TEST(BondedChain, UndampedEnergyIsConservedToRoundOff) {
  const int n = 50;
  World world = chain(n);
  demcal::Rng rng(5);
  for (int i = 0; i < n; ++i) world.bodies.vx[i] = rng.uniform(-1e-3, 1e-3);
  const double m = kDensity * M_PI * kRadius * kRadius;
  const double k = kBondModulus;
  // Leapfrog's invariant for a linear chain: sum m v(t - dt/2) v(t + dt/2) / 2
  // plus the bond energy F^2 / 2k at time t.
  auto energy_after_step = [&](const std::vector<double>& v_before) {
    double e = 0;
    for (int i = 0; i < n; ++i) e += 0.5 * m * v_before[i] * world.bodies.vx[i];
    for (std::size_t b = 0; b < world.pairs().size(); ++b) e += 0.5 * std::pow(world.pair_state(b, "bond_normal_force_n"), 2) / k;
    return e;
  };
  std::vector<double> before = world.bodies.vx;
  world.step();
  const double e0 = energy_after_step(before);
  double worst = 0;
  for (int s = 0; s < 10000; ++s) {
    before = world.bodies.vx;
    world.step();
    worst = std::max(worst, std::abs(energy_after_step(before) - e0) / e0);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(e0, 0.0);
}
