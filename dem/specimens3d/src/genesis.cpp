#include "demcal/dem3d/genesis.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::uint8_t kSphereGroup = 0, kWallGroup = 1;

void set_radius(Spheres& s, std::size_t i, double radius, double density) {
  s.radius[i] = radius;
  s.mass[i] = density * 4.0 / 3.0 * M_PI * radius * radius * radius;
  s.inertia[i] = 0.4 * s.mass[i] * radius * radius;
}

// Contacts per sphere, walls included, from the current overlaps, by sphere
// id (the world reorders its spheres at every rebuild, so an index would go
// stale).
std::vector<int> contact_counts(const World& world) {
  const Spheres& s = world.spheres;
  std::vector<int> count(s.size(), 0);
  const dem::ContactSet& c = world.pairs();
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
    const Vec3 d = s.position(j) - s.position(i);
    if (norm(d) < s.radius[i] + s.radius[j]) ++count[s.id[i]], ++count[s.id[j]];
  }
  const dem::ContactSet& w = world.wall_pairs();
  for (std::size_t k = 0; k < w.size(); ++k) {
    const auto i = static_cast<std::size_t>(w.i[k]);
    if (world.walls[static_cast<std::size_t>(w.j[k])].contact(s.position(i), s.radius[i]).overlap_m > 0) ++count[s.id[i]];
  }
  return count;
}

bool cycle_to_equilibrium(World& world, double ratio, std::uint64_t max_steps) {
  for (std::uint64_t done = 0; done < max_steps; done += 50) {
    world.run(50);
    if (world.force_ratio() < ratio) return true;
  }
  return false;
}

// A point drawn uniformly inside the vessel, `r` from its walls.
Vec3 random_point(const SphereSpecimenSpec& spec, double r, Rng& rng) {
  const double z = rng.uniform(r, spec.height_m - r);
  if (spec.vessel == Vessel::box) return {rng.uniform(r, spec.width_m - r), rng.uniform(r, spec.depth_m - r), z};
  const double reach = 0.5 * spec.width_m - r;
  for (;;) {  // by rejection from the square around the disc
    const double x = rng.uniform(-reach, reach), y = rng.uniform(-reach, reach);
    if (x * x + y * y <= reach * reach) return {x, y, z};
  }
}

}  // namespace

double SphereSpecimenSpec::volume_m3() const {
  if (vessel == Vessel::box) return width_m * depth_m * height_m;
  return M_PI * 0.25 * width_m * width_m * height_m;
}

std::size_t SphereSpecimenSpec::sphere_count() const {
  // E[r^3] of radii uniform in [a, b]: (b^4 - a^4) / (4 (b - a)); a^3 when a = b.
  const double a = radius_min_m, b = radius_max_m;
  const double mean_cube = b > a ? (b * b * b * b - a * a * a * a) / (4 * (b - a)) : a * a * a;
  return static_cast<std::size_t>(std::floor(volume_m3() * (1 - porosity) / (4.0 / 3.0 * M_PI * mean_cube)));
}

std::string SphereSpecimenSpec::cache_key() const {
  std::ostringstream key;
  // The version changes with anything that moves a packing's numbers.
  key << "genesis3d-v3 vessel=" << (vessel == Vessel::box ? "box" : "cylinder") << " W=" << format_double(width_m)
      << " D=" << format_double(vessel == Vessel::box ? depth_m : width_m) << " H=" << format_double(height_m)
      << " n=" << format_double(porosity) << " Rmin=" << format_double(radius_min_m)
      << " Rmax=" << format_double(radius_max_m) << " rho=" << format_double(density_kg_m3)
      << " E=" << format_double(genesis_modulus_pa) << " nc=" << min_contacts << " seed=" << seed;
  return key.str();
}

void SphereSpecimenSpec::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw Error(std::string("specimen: ") + name + " must be positive (got " + format_double(v) + ")");
  };
  positive(width_m, vessel == Vessel::box ? "width_m" : "diameter_m");
  if (vessel == Vessel::box) positive(depth_m, "depth_m");
  positive(height_m, "height_m");
  positive(radius_min_m, "radius_min_m");
  positive(radius_max_m, "radius_max_m");
  positive(density_kg_m3, "density_kg_m3");
  positive(genesis_modulus_pa, "genesis_modulus_pa");
  if (!(porosity > 0.2 && porosity < 0.6))
    throw Error("specimen: porosity must lie in (0.2, 0.6) for a 3D sphere packing (got " + format_double(porosity) + ")");
  if (radius_max_m < radius_min_m) throw Error("specimen: radius_max_m must be >= radius_min_m");
  const double narrowest = vessel == Vessel::box ? std::min({width_m, depth_m, height_m}) : std::min(width_m, height_m);
  if (radius_max_m * 6 > narrowest)
    throw Error("specimen: radius_max_m is too large for the specimen (need at least 6 radii across)");
  if (min_contacts < 1) throw Error("specimen: min_contacts must be at least 1");
  if (sphere_count() > 5000000) throw Error("specimen: more than 5 million spheres; use larger radii");
  if (sphere_count() < 10) throw Error("specimen: fewer than 10 spheres; use smaller radii");
}

SphereSpecimen pack_sphere_specimen(const SphereSpecimenSpec& spec) {
  spec.validate();
  Rng rng(spec.seed, 0x67656e33 /* "gen3" */);
  const std::size_t n = spec.sphere_count();
  const double volume = spec.volume_m3();

  // Final radii: uniform in [Rmin, Rmax], scaled so the solid volume gives the porosity exactly.
  std::vector<double> final_radius(n);
  double solid = 0;
  for (double& r : final_radius) {
    r = rng.uniform(spec.radius_min_m, spec.radius_max_m);
    solid += 4.0 / 3.0 * M_PI * r * r * r;
  }
  const double to_target = std::cbrt((1 - spec.porosity) * volume / solid);
  for (double& r : final_radius) r *= to_target;

  WorldSettings settings;
  settings.damping = 0.7;
  settings.skin_m = 0.25 * spec.radius_min_m;
  World world(settings);
  const std::uint8_t model = world.add_model(ContactModelRegistry::instance().create(
      "linear", {{"modulus_pa", spec.genesis_modulus_pa}, {"kn_ks", 1.0}, {"friction", 0.0}}, "genesis"));
  world.assign(kSphereGroup, kSphereGroup, model);
  world.assign(kSphereGroup, kWallGroup, model);
  world.spheres.reserve(n);
  // Start at 25 % solid fraction: m = ((1 - n) / (1 - n0))^(1/3) expands from there.
  const double start_scale = std::cbrt(0.25 / (1 - spec.porosity));
  for (std::size_t i = 0; i < n; ++i)
    world.spheres.add_sphere(random_point(spec, final_radius[i], rng), final_radius[i] * start_scale, spec.density_kg_m3,
                             kSphereGroup, static_cast<std::int64_t>(i));
  const double W = spec.width_m, D = spec.depth_m, H = spec.height_m;
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}, kWallGroup));
  world.walls.push_back(make_plane({0, 0, H}, {0, 0, -1}, kWallGroup));
  if (spec.vessel == Vessel::box) {
    world.walls.push_back(make_plane({0, 0, 0}, {1, 0, 0}, kWallGroup));
    world.walls.push_back(make_plane({W, 0, 0}, {-1, 0, 0}, kWallGroup));
    world.walls.push_back(make_plane({0, 0, 0}, {0, 1, 0}, kWallGroup));
    world.walls.push_back(make_plane({0, D, 0}, {0, -1, 0}, kWallGroup));
  } else {
    world.walls.push_back(make_cylinder({0, 0, -0.1 * H}, {0, 0, 1}, 0.5 * W, 1.2 * H, true, kWallGroup));
  }

  // Expansion in stages, cycling to near equilibrium after each. Radii are
  // set by id (the world stores the spheres in its own order).
  auto scale_radii = [&](double scale) {
    for (std::size_t i = 0; i < n; ++i)
      set_radius(world.spheres, i, final_radius[world.spheres.id[i]] * scale, spec.density_kg_m3);
    world.refresh();
  };
  const int stages = 10;
  // A large packing takes minutes: a progress line over the expansion stages
  // and the floater passes (with the particle-steps done).
  std::unique_ptr<Progress> progress;
  if (n >= 20000) {
    progress = std::make_unique<Progress>("genesis (" + std::to_string(n) + " spheres)", stages + 4);
    progress->set_units_name("particle-steps");
  }
  std::uint64_t steps_before = 0;
  auto advance = [&]() {
    if (!progress) return;
    progress->advance(1, static_cast<double>(n) * static_cast<double>(world.steps_done() - steps_before));
    steps_before = world.steps_done();
  };
  for (int stage = 1; stage <= stages; ++stage) {
    scale_radii(start_scale + (1 - start_scale) * stage / stages);
    cycle_to_equilibrium(world, stage < stages ? 2e-2 : 1e-3, 20000);
    advance();
  }

  // Floaters: grow them a little at a time; drop the few that still float,
  // and scale the kept spheres back to the porosity asked.
  std::vector<int> count;
  for (int pass = 0; pass < 4; ++pass) {
    count = contact_counts(world);
    for (int round = 0; round < 10; ++round) {
      bool any = false;
      Spheres& s = world.spheres;
      for (std::size_t i = 0; i < n; ++i)
        if (count[s.id[i]] < spec.min_contacts && s.radius[i] < 1.05 * final_radius[s.id[i]]) {
          set_radius(s, i, s.radius[i] * 1.005, spec.density_kg_m3);
          any = true;
        }
      if (!any) break;
      world.refresh();
      world.run(200);
      count = contact_counts(world);
    }
    double kept_solid = 0;
    const Spheres& s = world.spheres;
    for (std::size_t i = 0; i < n; ++i)
      if (count[s.id[i]] >= spec.min_contacts) kept_solid += 4.0 / 3.0 * M_PI * s.radius[i] * s.radius[i] * s.radius[i];
    const double target_solid = (1 - spec.porosity) * volume;
    if (std::abs(kept_solid / target_solid - 1) < 1e-3) break;
    const double grow = std::cbrt(target_solid / kept_solid);
    for (std::size_t i = 0; i < n; ++i)
      if (count[s.id[i]] >= spec.min_contacts) set_radius(world.spheres, i, s.radius[i] * grow, spec.density_kg_m3);
    world.refresh();
    cycle_to_equilibrium(world, 1e-3, 20000);
    advance();
  }
  if (progress) progress->finish();
  // The floaters of the packing as it ends (the last pass may have grown and cycled it).
  count = contact_counts(world);

  // The kept spheres, numbered in the world's order (a Morton curve of their
  // positions: neighbours close in memory when a test loads them).
  SphereSpecimen out;
  out.vessel = spec.vessel;
  out.width_m = W;
  out.depth_m = spec.vessel == Vessel::box ? D : W;
  out.height_m = H;
  out.density_kg_m3 = spec.density_kg_m3;
  const Spheres& s = world.spheres;
  std::vector<std::int64_t> kept_index(n, -1);
  double kept_solid = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (count[s.id[i]] < spec.min_contacts) {
      ++out.floaters_removed;
      continue;
    }
    kept_index[i] = static_cast<std::int64_t>(out.x.size());
    out.x.push_back(s.x[i]), out.y.push_back(s.y[i]), out.z.push_back(s.z[i]);
    out.radius.push_back(s.radius[i]);
    kept_solid += 4.0 / 3.0 * M_PI * s.radius[i] * s.radius[i] * s.radius[i];
  }
  out.porosity = 1 - kept_solid / volume;
  std::size_t contacts = 0;
  double overlap_ratio_sum = 0;
  const dem::ContactSet& pairs = world.pairs();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto i = static_cast<std::size_t>(pairs.i[k]), j = static_cast<std::size_t>(pairs.j[k]);
    if (kept_index[i] < 0 || kept_index[j] < 0) continue;
    const double overlap = s.radius[i] + s.radius[j] - norm(s.position(j) - s.position(i));
    if (overlap <= 0) continue;
    ++contacts;
    overlap_ratio_sum += overlap / std::min(s.radius[i], s.radius[j]);
  }
  out.coordination_number = out.size() ? 2.0 * static_cast<double>(contacts) / static_cast<double>(out.size()) : 0.0;
  out.mean_overlap_ratio = contacts ? overlap_ratio_sum / static_cast<double>(contacts) : 0.0;
  out.steps = world.steps_done();
  // Frictionless spheres without gravity jam only near random close packing:
  // a looser porosity leaves them apart, held by nothing.
  if (out.coordination_number < 3)
    throw Error("specimen: at porosity " + format_double(spec.porosity) + " the packing did not jam (" +
                format_double(out.coordination_number) +
                " contacts per sphere); a frictionless packing needs a porosity near random close packing, about "
                "0.36 for radii in a 1:1.5 range");
  if (std::abs(out.porosity - spec.porosity) > 0.005)
    throw Error("specimen: genesis reached porosity " + format_double(out.porosity) + ", not the " +
                format_double(spec.porosity) + " asked (" + std::to_string(out.floaters_removed) +
                " floaters removed); use a wider size range or another porosity");
  return out;
}

}  // namespace demcal::dem3d
