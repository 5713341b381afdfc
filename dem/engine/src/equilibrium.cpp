#include "demcal/dem/equilibrium.hpp"

#include <cmath>

namespace demcal::dem {
namespace {

// Calls f(model, block, local index, overlap m, centre distance m) for every disk pair.
template <typename F>
void for_each_disk_pair(const World& world, F f) {
  const Bodies& b = world.bodies;
  const ContactSet& pairs = world.pairs();
  for (std::size_t k = 0; k < pairs.size();) {
    const std::uint8_t m = pairs.model[k];
    const ConstPairBlock c = pairs.block(m);
    for (std::size_t local = 0; local < c.size; ++local, ++k) {
      const std::size_t i = static_cast<std::size_t>(c.i[local]), j = static_cast<std::size_t>(c.j[local]);
      const double dx = b.x[j] - b.x[i], dy = b.y[j] - b.y[i];
      const double distance = centre_distance_m(dx, dy);
      f(world.model(m), c, local, disk_overlap_m(b.radius[i], b.radius[j], distance), distance);
    }
  }
}

// PFC's ratio over the disks `counts` admits (not in clumps) and, when `clumps`, each clump as one body; the
// contact side over the touching disk pairs `pair_counts` admits. Gravity counts: the integration adds it, so a
// body at rest under gravity has contact forces that balance its weight, not zero.
template <typename DiskFilter, typename PairFilter>
double ratio_over(const World& world, DiskFilter counts, bool clumps, PairFilter pair_counts) {
  const Bodies& b = world.bodies;
  const double gx = world.settings().gravity_x_m_s2, gy = world.settings().gravity_y_m_s2;
  double unbalanced = 0;
  std::size_t free_bodies = 0;
  // In the order of the bodies' ids: the bits do not depend on how they are stored.
  for (std::size_t i : disks_by_id(b))
    if (b.clump[i] < 0 && counts(i)) {
      unbalanced += std::hypot(b.fx[i] + b.mass[i] * gx, b.fy[i] + b.mass[i] * gy);
      ++free_bodies;
    }
  if (clumps)
    for (std::size_t c : clumps_by_id(world)) {
      const Clump& clump = world.clumps()[c];
      double fx = clump.mass * gx, fy = clump.mass * gy;
      for (std::size_t i : clump.members) {
        fx += b.fx[i];
        fy += b.fy[i];
      }
      unbalanced += std::hypot(fx, fy);
      ++free_bodies;
    }
  double contact = 0;
  std::size_t touching = 0;
  for_each_disk_pair(world, [&](const ContactModel& model, const ConstPairBlock& c, std::size_t k, double overlap, double) {
    if (overlap <= 0) return;
    if (!pair_counts(static_cast<std::size_t>(c.i[k]), static_cast<std::size_t>(c.j[k]))) return;
    const double fn = model.normal_force_n(c, k, overlap);
    if (fn <= 0) return;
    contact += fn;
    ++touching;
  });
  if (touching == 0 || free_bodies == 0) return 0.0;
  return (unbalanced / static_cast<double>(free_bodies)) / (contact / static_cast<double>(touching));
}

}  // namespace

double force_ratio(const World& world) {
  // Per body: each disk not in a clump (fixed ones included), and each clump as one (its members' own forces do
  // not balance, the clump's sum does).
  return ratio_over(world, [](std::size_t) { return true; }, true, [](std::size_t, std::size_t) { return true; });
}

double force_ratio(const World& world, std::uint8_t group) {
  const Bodies& b = world.bodies;
  return ratio_over(
      world, [&](std::size_t i) { return b.group[i] == group && !b.fixed[i]; }, false,
      [&](std::size_t i, std::size_t j) { return b.group[i] == group || b.group[j] == group; });
}

bool cycle_to_equilibrium(World& world, double ratio, std::uint64_t max_steps) {
  for (std::uint64_t done = 0; done < max_steps; done += 50) {
    world.run(50);
    if (force_ratio(world) < ratio) return true;
  }
  return false;
}

double contact_mean_stress_pa(const World& world, double area_m2) {
  double sum = 0;
  for_each_disk_pair(world, [&](const ContactModel& model, const ConstPairBlock& c, std::size_t k, double overlap,
                                double distance) {
    if (overlap > 0) sum += model.normal_force_n(c, k, overlap) * distance;
  });
  return sum / (2.0 * area_m2 * world.settings().thickness_m);
}

}  // namespace demcal::dem
