#include "demcal/dem3d/spheres.hpp"

#include <cmath>

#include "demcal/core/error.hpp"

namespace demcal::dem3d {

namespace {

template <typename T>
void permute_array(std::vector<T>& values, const std::vector<std::size_t>& order) {
  std::vector<T> out(values.size());
  for (std::size_t k = 0; k < order.size(); ++k) out[k] = values[order[k]];
  values.swap(out);
}

}  // namespace

std::size_t Spheres::add_sphere(Vec3 centre_m, double radius_m, double density_kg_m3, std::uint8_t material_group,
                                std::int64_t stable_id) {
  if (!(radius_m > 0) || !(density_kg_m3 > 0)) throw Error("a sphere needs a positive radius and density");
  const double m = density_kg_m3 * 4.0 / 3.0 * M_PI * radius_m * radius_m * radius_m;
  x.push_back(centre_m.x), y.push_back(centre_m.y), z.push_back(centre_m.z);
  for (auto* v : {&vx, &vy, &vz, &wx, &wy, &wz}) v->push_back(0.0);
  radius.push_back(radius_m);
  mass.push_back(m);
  inertia.push_back(0.4 * m * radius_m * radius_m);
  group.push_back(material_group);
  fixed.push_back(0);
  clump.push_back(-1);
  id.push_back(static_cast<std::uint32_t>(stable_id >= 0 ? stable_id : static_cast<std::int64_t>(x.size() - 1)));
  return x.size() - 1;
}

void Spheres::reserve(std::size_t n) {
  for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz, &radius, &mass, &inertia}) v->reserve(n);
  group.reserve(n), fixed.reserve(n), clump.reserve(n), id.reserve(n);
}

void Spheres::permute(const std::vector<std::size_t>& order) {
  for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz, &radius, &mass, &inertia}) permute_array(*v, order);
  permute_array(group, order), permute_array(fixed, order), permute_array(clump, order), permute_array(id, order);
}

}  // namespace demcal::dem3d
