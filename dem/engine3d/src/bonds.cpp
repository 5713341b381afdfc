// The 3D world's bonds: installing them at material genesis, the log of
// their breaks, and how loaded they are. A bond's pair stays in the
// neighbour list however far apart its spheres move (neighbour_grid.cpp).
#include <algorithm>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem3d/world.hpp"
#include "world_internals.hpp"

namespace demcal::dem3d {

std::size_t World::install_bonds(double tolerance_m, std::uint64_t seed, double locked_in_fraction) {
  if (!(locked_in_fraction >= 0 && locked_in_fraction <= 1))
    throw Error("install_bonds: the locked-in fraction must lie in [0, 1]");
  if (!(tolerance_m >= 0)) throw Error("install_bonds: the gap tolerance must be >= 0");
  if (skin_m_ <= 0) rebuild();  // sets the skin
  // Every pair within the tolerance must be in the list: the search reaches
  // one skin, so for the bonding it reaches the tolerance too.
  const double skin = skin_m_;
  skin_m_ = std::max(skin_m_, tolerance_m);
  rebuild();
  skin_m_ = skin;
  std::size_t installed = 0;
  for (std::uint8_t m : run_models_) {
    PairBlock block = pairs_.block(m);
    for (std::size_t k = 0; k < block.size; ++k) {
      const auto i = static_cast<std::size_t>(block.i[k]), j = static_cast<std::size_t>(block.j[k]);
      // The overlap as the force loop computes it, so a force-free pair is exactly force-free.
      const Vec3 d = spheres.position(j) - spheres.position(i);
      const double overlap = spheres.radius[i] + spheres.radius[j] - std::sqrt(dot(d, d));
      if (overlap > 0) models_[m]->make_force_free(block, k, overlap * (1 - locked_in_fraction));
      if (-overlap > tolerance_m) continue;
      PairInfo info;
      info.radius_i = spheres.radius[i], info.radius_j = spheres.radius[j];
      info.group_i = spheres.group[i], info.group_j = spheres.group[j];
      info.overlap_m = overlap;
      const std::uint32_t a = spheres.id[i], b = spheres.id[j];
      Rng rng(keyed_seed(seed, std::min(a, b), std::max(a, b)), 0x626f6e64 /* "bond" */);
      installed += models_[m]->install_bond(block, k, info, rng) ? 1 : 0;
    }
  }
  // Bonded pairs outside the skin now stay by their bonds; the rest go.
  rebuild();  // bonds stiffen the spheres: a new time step
  return installed;
}

std::size_t World::make_wall_contacts_force_free() {
  rebuild();
  compute_wall_geometry();
  const WallGeometryArrays& g = internals_->wall_geometry;
  std::size_t touching = 0;
  for (std::uint8_t m : wall_run_models_) {
    PairBlock block = wall_pairs_.block(m);
    const std::size_t first = wall_pairs_.begin(m);
    for (std::size_t k = 0; k < block.size; ++k) {
      const double overlap = g.overlap[first + k];
      if (!(overlap > 0)) continue;
      models_[m]->make_force_free(block, k, overlap);
      ++touching;
    }
  }
  return touching;
}

void World::start_test() {
  breaks_.clear();
  steps_ = 0;
  time_s_ = 0;
  for (auto* v : {&spheres.vx, &spheres.vy, &spheres.vz, &spheres.wx, &spheres.wy, &spheres.wz})
    std::fill(v->begin(), v->end(), 0.0);
  for (Clump& c : clumps_) c.velocity_m_s = c.angular_momentum = {};
}

void World::log_breaks() {
  for (std::uint8_t m : run_models_) {
    if (!models_[m]->has_bonds()) continue;
    for (std::size_t k = pairs_.begin(m); k < pairs_.end(m); ++k) {
      dem::PairFlags& flags = pairs_.flags[k];
      if (!(flags & kBrokeThisStep)) continue;
      const auto i = static_cast<std::size_t>(pairs_.i[k]), j = static_cast<std::size_t>(pairs_.j[k]);
      // The contact point: the middle of the overlap (or of the gap).
      const Vec3 d = spheres.position(j) - spheres.position(i);
      const double distance = std::sqrt(dot(d, d));
      const double arm = spheres.radius[i] - 0.5 * (spheres.radius[i] + spheres.radius[j] - distance);
      const Vec3 at = distance > 0 ? spheres.position(i) + (arm / distance) * d : spheres.position(i);
      const unsigned tension = tension_breaks(flags), shear = shear_breaks(flags);
      for (unsigned b = 0; b < tension + shear; ++b)
        breaks_.push_back({time_s_, at.x, at.y, b < tension ? dem::BreakMode::Tension : dem::BreakMode::Shear,
                           spheres.group[i], spheres.group[j], at.z});
      flags &= ~kBreakMarks;
    }
  }
}

std::size_t World::bonded_pairs() const {
  std::size_t n = 0;
  for (dem::PairFlags f : pairs_.flags) n += (f & dem::kBonded) != 0;
  return n;
}

double World::max_bond_utilisation() const {
  double most = std::nan("");
  for (std::size_t m = 0; m < models_.size(); ++m) {
    if (!models_[m]->has_bonds()) continue;
    const double u = models_[m]->max_bond_utilisation(pairs_.block(static_cast<std::uint8_t>(m)), spheres);
    if (std::isnan(most) || u > most) most = u;
  }
  return most;
}

}  // namespace demcal::dem3d
