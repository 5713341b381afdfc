#include "demcal/dem/bodies.hpp"

#include <algorithm>
#include <cmath>

namespace demcal::dem {

std::size_t Bodies::add_disk(double x_m, double y_m, double radius_m, double density_kg_m3, double thickness_m,
                             std::uint8_t material_group, std::int64_t stable_id) {
  x.push_back(x_m);
  y.push_back(y_m);
  vx.push_back(0.0);
  vy.push_back(0.0);
  w.push_back(0.0);
  fx.push_back(0.0);
  fy.push_back(0.0);
  moment.push_back(0.0);
  radius.push_back(radius_m);
  double m = density_kg_m3 * M_PI * radius_m * radius_m * thickness_m;
  mass.push_back(m);
  inertia.push_back(0.5 * m * radius_m * radius_m);  // solid disk
  group.push_back(material_group);
  fixed.push_back(0);
  clump.push_back(-1);
  id.push_back(static_cast<std::uint32_t>(stable_id >= 0 ? stable_id : static_cast<std::int64_t>(x.size() - 1)));
  return x.size() - 1;
}

void Bodies::clear_forces() {
  std::fill(fx.begin(), fx.end(), 0.0);
  std::fill(fy.begin(), fy.end(), 0.0);
  std::fill(moment.begin(), moment.end(), 0.0);
}

void Bodies::reserve(std::size_t n) {
  for (auto* v : {&x, &y, &vx, &vy, &w, &fx, &fy, &moment, &radius, &mass, &inertia}) v->reserve(n);
  group.reserve(n);
  fixed.reserve(n);
  clump.reserve(n);
  id.reserve(n);
}

}  // namespace demcal::dem
