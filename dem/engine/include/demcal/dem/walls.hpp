#pragma once
// Straight walls (loading platens, confinement): segments that move rigidly
// under velocity control or a stress servo, and collect the contact forces
// the disks exert on them.
#include <cstddef>
#include <string>
#include <vector>

namespace demcal::dem {

// The walls of a box (a packing's vessel; a lab test's platens and side
// walls), by role: every box is built in this order.
enum BoxWall : std::size_t { kBottomWall = 0, kTopWall = 1, kLeftWall = 2, kRightWall = 3 };

struct Wall {
  std::string name;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // end points, m
  double vx = 0, vy = 0;                  // velocity, m/s
  std::uint8_t group = 0;                 // material group of the wall
  bool active = true;                     // removed walls stay in the list, inactive
  // Force the disks exert on the wall in the last step, N.
  double fx = 0, fy = 0;
  // Servo control along the wall's inward normal: when `servo` is set the
  // velocity is gain * (target - measured) stress, clipped to max speed.
  bool servo = false;
  double servo_target_stress_pa = 0;
  double servo_gain_m_s_per_pa = 0;
  double servo_max_speed_m_s = 0;
  double servo_length_m = 0;              // loaded length for the stress, m (times thickness)
  double inward_nx = 0, inward_ny = 0;    // unit normal pointing into the specimen

  double length() const;
  // Moves the end points by the velocity times dt.
  void advance(double dt);
};

}  // namespace demcal::dem
