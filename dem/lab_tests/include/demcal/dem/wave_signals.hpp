#pragma once
// What a dynamic test reads off a recorded velocity history: when a wave
// arrives, how fast it travels, how much of it comes back, and when a point
// falls quiet again. Histories are sampled at times t (increasing).
#include <vector>

namespace demcal::dem {

// The time after which |v| stays below `threshold` (interpolated to the
// crossing); 0 when it never reaches it. `recovered` is false when |v| is
// still above it at the last sample: the time is then the last sample's.
struct Recovery {
  double time_s = 0;
  bool recovered = true;
};
Recovery recovery_time(const std::vector<double>& t, const std::vector<double>& speed, double threshold);

// First time v rises through `level` (> 0), interpolated; NaN when it never does.
double first_crossing(const std::vector<double>& t, const std::vector<double>& v, double level);

// Least-squares slope of position on arrival time (a wave's speed), from two
// or more arrivals; NaN when fewer than two arrivals are finite.
double arrival_speed(const std::vector<double>& x, const std::vector<double>& arrival_t);

// The value of largest magnitude (its sign kept) among the samples with
// from <= t < to; 0 when there are none.
double signed_extreme(const std::vector<double>& t, const std::vector<double>& v, double from, double to);

}  // namespace demcal::dem
