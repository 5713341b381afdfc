#pragma once
// A rigid clump of disks (a concrete aggregate): it moves as one body with the
// mass and inertia of its shape, not of its disks; its disks only carry its
// contacts, and pairs inside one clump are never in contact.
#include <cstddef>
#include <vector>

namespace demcal::dem {

struct Clump {
  double x = 0, y = 0;          // centre of mass, m
  double vx = 0, vy = 0, w = 0;  // velocity (t - dt/2), rad/s
  double mass = 0, inertia = 0;  // kg, kg m^2 (about the centre of mass)
  std::vector<std::size_t> members;       // disk indices
  std::vector<double> offset_x, offset_y;  // member centre minus clump centre, current orientation
};

}  // namespace demcal::dem
