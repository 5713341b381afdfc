#pragma once
// Shifted benchmark functions with known minima (value 0 at `shift`) and a
// batch objective that fails the test if an optimiser leaves the bounds.
#include <gtest/gtest.h>

#include <cmath>

#include "demcal/inverse/optimizer.hpp"

namespace demcal::test {

inline double shifted_rosenbrock(const inverse::Point& x, const inverse::Point& shift) {
  double f = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    double a = x[i] - shift[i] + 1.0, b = x[i + 1] - shift[i + 1] + 1.0;
    f += 100.0 * (b - a * a) * (b - a * a) + (1.0 - a) * (1.0 - a);
  }
  return f;
}

inline double shifted_rastrigin(const inverse::Point& x, const inverse::Point& shift) {
  double f = 10.0 * static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    double z = x[i] - shift[i];
    f += z * z - 10.0 * std::cos(2.0 * M_PI * z);
  }
  return f;
}

template <typename F>
inverse::BatchObjective checked(F f, const inverse::Bounds& bounds, long* outside) {
  return [f, bounds, outside](const std::vector<inverse::Point>& points, std::vector<double>& values) {
    values.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!bounds.contains(points[i])) ++*outside;
      values[i] = f(points[i]);
    }
  };
}

inline inverse::Bounds box(std::size_t n, double low, double high) {
  return {inverse::Point(n, low), inverse::Point(n, high)};
}

}  // namespace demcal::test
