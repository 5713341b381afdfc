#include "demcal/dem/genesis.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem/equilibrium.hpp"
#include "demcal/dem/spatial_order.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

constexpr std::uint8_t kDiskGroup = 0, kWallGroup = 1;

// Contacts per disk, walls included, from the current overlaps.
std::vector<int> contact_counts(const World& world) {
  const Bodies& b = world.bodies;
  std::vector<int> count(b.size(), 0);
  const ContactSet& c = world.pairs();
  for (std::size_t k = 0; k < c.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
    if (b.radius[i] + b.radius[j] > std::hypot(b.x[j] - b.x[i], b.y[j] - b.y[i])) {
      ++count[i];
      ++count[j];
    }
  }
  const ContactSet& w = world.wall_pairs();
  for (std::size_t k = 0; k < w.size(); ++k)
    if (w.flags[k] & kTouching) ++count[static_cast<std::size_t>(w.i[k])];
  return count;
}

// v[k] becomes v[order[k]].
void permute(std::vector<double>& v, const std::vector<std::size_t>& order) {
  std::vector<double> sorted(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) sorted[k] = v[order[k]];
  v.swap(sorted);
}

void set_radius(Bodies& b, std::size_t i, double radius, double density, double thickness) {
  b.radius[i] = radius;
  b.mass[i] = density * M_PI * radius * radius * thickness;
  b.inertia[i] = 0.5 * b.mass[i] * radius * radius;
}

Wall make_wall(double x0, double y0, double x1, double y1, double nx, double ny) {
  Wall wall;
  wall.x0 = x0;
  wall.y0 = y0;
  wall.x1 = x1;
  wall.y1 = y1;
  wall.group = kWallGroup;
  wall.inward_nx = nx;
  wall.inward_ny = ny;
  return wall;
}

// Servo-controlled walls bring the mean wall stress to the spec's isotropic stress.
void servo_to_isotropic_stress(World& world, const SpecimenSpec& spec) {
  const double r_mean = 0.5 * (spec.radius_min_m + spec.radius_max_m);
  for (Wall& wall : world.walls) {
    wall.servo = true;
    wall.servo_target_stress_pa = spec.isotropic_stress_pa;
    // Each step closes about 5 % of the stress error (wall stiffness ~ E t L / R).
    wall.servo_gain_m_s_per_pa = 0.05 * r_mean / (spec.genesis_modulus_pa * world.dt_s());
    wall.servo_max_speed_m_s = 0.01 * r_mean / world.dt_s();
  }
  auto wall_stress = [&](const Wall& wall, double loaded_length) {
    return -(wall.fx * wall.inward_nx + wall.fy * wall.inward_ny) / (loaded_length * spec.thickness_m);
  };
  for (int round = 0; round < 400; ++round) {
    const double w_now = world.wall(kRightWall).x0 - world.wall(kLeftWall).x0;
    const double h_now = world.wall(kTopWall).y0 - world.wall(kBottomWall).y0;
    world.wall(kBottomWall).servo_length_m = world.wall(kTopWall).servo_length_m = w_now;
    world.wall(kLeftWall).servo_length_m = world.wall(kRightWall).servo_length_m = h_now;
    world.run(50);
    bool reached = true;
    for (int w = 0; w < 4; ++w) {
      double s = wall_stress(world.walls[static_cast<std::size_t>(w)], w < 2 ? w_now : h_now);
      reached = reached && std::abs(s - spec.isotropic_stress_pa) <= spec.stress_tolerance * spec.isotropic_stress_pa;
    }
    if (reached && force_ratio(world) < 1e-3) break;
  }
  for (Wall& wall : world.walls) {
    wall.servo = false;
    wall.vx = wall.vy = 0;
  }
}

}  // namespace

std::size_t SpecimenSpec::disk_count() const {
  const double r_mean = 0.5 * (radius_min_m + radius_max_m);
  return static_cast<std::size_t>(std::floor(width_m * height_m * (1 - porosity) / (M_PI * r_mean * r_mean)));
}

std::string SpecimenSpec::cache_key() const {
  std::ostringstream key;
  // The version changes with anything that moves a packing's numbers (the
  // engine's arithmetic too), so a cache never serves an older packing.
  key << "genesis-v5 W=" << format_double(width_m) << " H=" << format_double(height_m)
      << " t=" << format_double(thickness_m) << " n=" << format_double(porosity) << " Rmin=" << format_double(radius_min_m)
      << " Rmax=" << format_double(radius_max_m) << " rho=" << format_double(density_kg_m3)
      << " E=" << format_double(genesis_modulus_pa) << " s0=" << format_double(isotropic_stress_pa)
      << " tol=" << format_double(stress_tolerance) << " nc=" << min_contacts << " seed=" << seed;
  return key.str();
}

void SpecimenSpec::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw Error(std::string("specimen: ") + name + " must be positive (got " + format_double(v) + ")");
  };
  positive(width_m, "width_m");
  positive(height_m, "height_m");
  positive(thickness_m, "thickness_m");
  positive(radius_min_m, "radius_min_m");
  positive(radius_max_m, "radius_max_m");
  positive(density_kg_m3, "density_kg_m3");
  positive(genesis_modulus_pa, "genesis_modulus_pa");
  if (!(locked_in_stress_pa >= 0) || !std::isfinite(locked_in_stress_pa))
    throw Error("specimen: locked_in_stress_pa must be zero or positive (got " + format_double(locked_in_stress_pa) + ")");
  if (!(isotropic_stress_pa >= 0) || !std::isfinite(isotropic_stress_pa))
    throw Error("specimen: isotropic_stress_pa must be zero (a fixed vessel) or positive (got " +
                format_double(isotropic_stress_pa) + ")");
  if (!(porosity > 0.05 && porosity < 0.5))
    throw Error("specimen: porosity must lie in (0.05, 0.5) for a 2D disk packing (got " + format_double(porosity) + ")");
  if (radius_max_m < radius_min_m) throw Error("specimen: radius_max_m must be >= radius_min_m");
  if (radius_max_m * 6 > std::min(width_m, height_m))
    throw Error("specimen: radius_max_m is too large for the specimen (need at least 6 radii across)");
  if (disk_count() > 5000000) throw Error("specimen: more than 5 million disks; use larger radii");
  if (disk_count() < 10) throw Error("specimen: fewer than 10 disks; use smaller radii");
}

Specimen pack_specimen(const SpecimenSpec& spec) {
  spec.validate();
  Rng rng(spec.seed, 0x67656e65 /* "gene" */);
  const std::size_t n = spec.disk_count();
  const double area = spec.width_m * spec.height_m;

  // Final radii: uniform in [Rmin, Rmax], scaled so the solid area gives the porosity exactly.
  std::vector<double> final_radius(n);
  double solid = 0;
  for (double& r : final_radius) {
    r = rng.uniform(spec.radius_min_m, spec.radius_max_m);
    solid += M_PI * r * r;
  }
  const double to_target = std::sqrt((1 - spec.porosity) * area / solid);
  for (double& r : final_radius) r *= to_target;

  WorldSettings settings;
  settings.thickness_m = spec.thickness_m;
  settings.damping = 0.7;
  settings.skin_m = 0.25 * spec.radius_min_m;
  World world(settings);
  const std::uint8_t model = world.add_model(ContactModelRegistry::instance().create(
      "linear", {{"modulus_pa", spec.genesis_modulus_pa}, {"kn_ks", 1.0}, {"friction", 0.0}}, "genesis"));
  world.assign(kDiskGroup, kDiskGroup, model);
  world.assign(kDiskGroup, kWallGroup, model);
  world.bodies.reserve(n);
  // Start at 30 % solid fraction: m = sqrt((1 - n) / (1 - n0)) expands from there.
  const double start_scale = std::sqrt(0.30 / (1 - spec.porosity));
  std::vector<double> start_x(n), start_y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = final_radius[i];
    start_x[i] = rng.uniform(r, spec.width_m - r);
    start_y[i] = rng.uniform(r, spec.height_m - r);
  }
  // Numbered along a Hilbert curve, so that neighbours sit close in memory
  // while packing (the disks move less than their size from here).
  const std::vector<std::size_t> start_order = hilbert_order(start_x, start_y);
  permute(final_radius, start_order);
  for (std::size_t k = 0; k < n; ++k)
    world.bodies.add_disk(start_x[start_order[k]], start_y[start_order[k]], final_radius[k] * start_scale,
                          spec.density_kg_m3, spec.thickness_m, kDiskGroup);
  const double W = spec.width_m, H = spec.height_m, margin = 0.1 * std::max(W, H);
  world.walls.push_back(make_wall(-margin, 0, W + margin, 0, 0, 1));        // bottom
  world.walls.push_back(make_wall(-margin, H, W + margin, H, 0, -1));       // top
  world.walls.push_back(make_wall(0, -margin, 0, H + margin, 1, 0));        // left
  world.walls.push_back(make_wall(W, -margin, W, H + margin, -1, 0));       // right

  // Expansion in stages, cycling to near equilibrium after each.
  const int stages = 10;
  for (int stage = 1; stage <= stages; ++stage) {
    const double scale = start_scale + (1 - start_scale) * stage / stages;
    for (std::size_t i = 0; i < n; ++i)
      set_radius(world.bodies, i, final_radius[i] * scale, spec.density_kg_m3, spec.thickness_m);
    world.refresh();
    cycle_to_equilibrium(world, stage < stages ? 2e-2 : 1e-3, 20000);
  }

  // Optional (P&C 2004): servo walls install an isotropic stress; the box
  // then moves, so the porosity becomes an outcome. Without it the vessel
  // stays fixed, as in PFC's `ball distribute`, and the porosity is the one asked.
  if (spec.isotropic_stress_pa > 0) servo_to_isotropic_stress(world, spec);

  // Floaters: grow them a little at a time; drop the few that still float.
  // In a fixed vessel the dropped disks' area would raise the porosity (each
  // is about 1 / N of the solid) and the grown ones' lower it, so the kept
  // disks then scale together to the porosity asked, and the floaters are
  // looked for again.
  std::vector<int> count;
  for (int pass = 0; pass < 4; ++pass) {
    count = contact_counts(world);
    for (int round = 0; round < 10; ++round) {
      bool any = false;
      for (std::size_t i = 0; i < n; ++i)
        if (count[i] < spec.min_contacts && world.bodies.radius[i] < 1.05 * final_radius[i]) {
          set_radius(world.bodies, i, world.bodies.radius[i] * 1.005, spec.density_kg_m3, spec.thickness_m);
          any = true;
        }
      if (!any) break;
      world.refresh();
      world.run(200);
      count = contact_counts(world);
    }
    if (spec.isotropic_stress_pa > 0) break;  // the porosity is an outcome there
    double kept_solid = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (count[i] >= spec.min_contacts) kept_solid += M_PI * world.bodies.radius[i] * world.bodies.radius[i];
    const double target_solid = (1 - spec.porosity) * area;
    if (std::abs(kept_solid / target_solid - 1) < 1e-3) break;
    const double grow = std::sqrt(target_solid / kept_solid);
    for (std::size_t i = 0; i < n; ++i)
      if (count[i] >= spec.min_contacts)
        set_radius(world.bodies, i, world.bodies.radius[i] * grow, spec.density_kg_m3, spec.thickness_m);
    world.refresh();
    cycle_to_equilibrium(world, 1e-3, 20000);
  }

  // The disks keep their radii and overlaps: the overlaps are the packing's
  // locked-in state at the genesis stiffness, and bond installation makes
  // each pair force-free as it lies (World::install_bonds), so they never
  // become forces of the test's stiffness.
  Specimen out;
  const Bodies& b = world.bodies;
  const double x0 = world.wall(kLeftWall).x0, y0 = world.wall(kBottomWall).y0;
  out.width_m = world.wall(kRightWall).x0 - x0;
  out.height_m = world.wall(kTopWall).y0 - y0;
  out.thickness_m = spec.thickness_m;
  out.density_kg_m3 = spec.density_kg_m3;
  std::vector<std::int64_t> kept_index(n, -1);
  double kept_solid = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (count[i] < spec.min_contacts) {
      ++out.floaters_removed;
      continue;
    }
    kept_index[i] = static_cast<std::int64_t>(out.x.size());
    out.x.push_back(b.x[i] - x0);
    out.y.push_back(b.y[i] - y0);
    out.radius.push_back(b.radius[i]);
    kept_solid += M_PI * b.radius[i] * b.radius[i];
  }
  // Porosity as PFC counts it: overlaps are not subtracted.
  out.porosity = 1 - kept_solid / (out.width_m * out.height_m);
  // Contacts between kept disks: how many per disk and how deep.
  std::size_t contacts = 0;
  double overlap_ratio_sum = 0;
  const ContactSet& pairs = world.pairs();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(pairs.i[k]), j = static_cast<std::size_t>(pairs.j[k]);
    if (kept_index[i] < 0 || kept_index[j] < 0) continue;
    const double overlap = b.radius[i] + b.radius[j] - std::hypot(b.x[j] - b.x[i], b.y[j] - b.y[i]);
    if (overlap <= 0) continue;
    ++contacts;
    overlap_ratio_sum += overlap / std::min(b.radius[i], b.radius[j]);
  }
  out.coordination_number = out.size() ? 2.0 * static_cast<double>(contacts) / static_cast<double>(out.size()) : 0.0;
  out.mean_overlap_ratio = contacts ? overlap_ratio_sum / static_cast<double>(contacts) : 0.0;
  out.steps = world.steps_done();
  // The specimen's numbering (its disks' ids in a test) follows space, so a
  // test's pair list walks memory in order (spatial_order.hpp).
  {
    const std::vector<std::size_t> order = hilbert_order(out.x, out.y);
    permute(out.x, order);
    permute(out.y, order);
    permute(out.radius, order);
  }
  if (spec.isotropic_stress_pa == 0 && std::abs(out.porosity - spec.porosity) > 0.005)
    throw Error("specimen: genesis reached porosity " + format_double(out.porosity) + ", not the " +
                format_double(spec.porosity) + " asked (" + std::to_string(out.floaters_removed) +
                " floaters removed); use a wider size range or another porosity");
  return out;
}

}  // namespace demcal::dem
