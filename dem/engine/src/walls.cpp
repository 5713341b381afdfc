#include "demcal/dem/walls.hpp"

#include <cmath>

namespace demcal::dem {

double Wall::length() const { return std::hypot(x1 - x0, y1 - y0); }

void Wall::advance(double dt) {
  x0 += vx * dt;
  x1 += vx * dt;
  y0 += vy * dt;
  y1 += vy * dt;
}

}  // namespace demcal::dem
