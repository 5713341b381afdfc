#pragma once
// The least-squares straight line y = intercept + slope x with its R^2: the
// strength envelopes of a biaxial series and the flanks of a heap both fit one.
#include <string>
#include <vector>

namespace demcal::dem {

struct FittedLine {
  double intercept = 0, slope = 0, r2 = 0;  // r2 is 1 when y does not vary
};

// Throws an Error `too_few` for fewer than two points (or x and y of
// different lengths) and `no_spread` when every x is the same.
FittedLine fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::string& too_few,
                    const std::string& no_spread);

}  // namespace demcal::dem
