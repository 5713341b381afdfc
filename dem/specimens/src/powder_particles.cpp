#include "demcal/dem/powder_particles.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

// Half the distance between a clump's disk centres.
double half_spacing(double radius_m, double aspect_ratio) { return radius_m * (aspect_ratio - 1.0); }

// The lens two circles of radius r share at centre distance d = 2c: two
// circular segments, each cut from its circle by the chord at distance c
// from its centre (half-angle alpha = acos(c / r)). Area and polar moment
// about the lens's centre, in closed form: a segment's polar moment about its
// circle's centre is r^4 (alpha / 2 - sin 2 alpha / 6 - sin 4 alpha / 24),
// its first moment (2/3) (r^2 - c^2)^(3/2), then the parallel axes to the chord.
void lens(double r, double d, double& area, double& polar) {
  area = polar = 0;
  if (d >= 2 * r) return;
  const double c = 0.5 * d, alpha = std::acos(c / r);
  const double segment_area = r * r * (alpha - std::sin(alpha) * std::cos(alpha));
  const double about_centre =
      r * r * r * r * (0.5 * alpha - std::sin(2 * alpha) / 6.0 - std::sin(4 * alpha) / 24.0);
  const double first_moment = 2.0 / 3.0 * std::pow(r * r - c * c, 1.5);
  area = 2 * segment_area;
  polar = 2 * (about_centre - 2 * c * first_moment + c * c * segment_area);
}

bool inside_convex(const std::vector<double>& p, double x, double y, double margin) {
  const std::size_t n = p.size() / 2;
  for (std::size_t k = 0; k < n; ++k) {
    const double x0 = p[2 * k], y0 = p[2 * k + 1], x1 = p[2 * ((k + 1) % n)], y1 = p[2 * ((k + 1) % n) + 1];
    const double ex = x1 - x0, ey = y1 - y0, len = std::hypot(ex, ey);
    // Counter-clockwise: inside is to the left of every edge, by at least the margin.
    if ((ex * (y - y0) - ey * (x - x0)) / len < margin) return false;
  }
  return true;
}

double polygon_area(const std::vector<double>& p) {
  const std::size_t n = p.size() / 2;
  double twice = 0;
  for (std::size_t k = 0; k < n; ++k)
    twice += p[2 * k] * p[2 * ((k + 1) % n) + 1] - p[2 * ((k + 1) % n)] * p[2 * k + 1];
  return 0.5 * twice;
}

}  // namespace

void PowderSpec::validate(const char* where) const {
  const std::string w(where);
  if (!(radius_min_m > 0 && radius_max_m >= radius_min_m && std::isfinite(radius_max_m)))
    throw Error(w + ": radius_min_m and radius_max_m must satisfy 0 < min <= max");
  if (!(density_kg_m3 > 0)) throw Error(w + ": density_kg_m3 must be positive");
  if (!(clump_aspect_ratio >= 1.0 && clump_aspect_ratio <= 2.0))
    throw Error(w + ": clump_aspect_ratio " + format_double(clump_aspect_ratio) +
                " must lie in [1, 2] (1: disks; a two-disk clump is at most twice as long as wide)");
  if (!(clump_fraction >= 0 && clump_fraction <= 1)) throw Error(w + ": clump_fraction must lie in [0, 1]");
  if (!(solids_fraction > 0 && solids_fraction <= 0.6))
    throw Error(w + ": solids_fraction must lie in (0, 0.6] (random placement without overlap jams near 0.55)");
}

double particle_area_m2(double r, double aspect_ratio, bool clump) {
  if (!clump || aspect_ratio <= 1.0) return M_PI * r * r;
  double area = 0, polar = 0;
  lens(r, 2 * half_spacing(r, aspect_ratio), area, polar);
  return 2 * M_PI * r * r - area;
}

double particle_polar_moment_m4(double r, double aspect_ratio, bool clump) {
  if (!clump || aspect_ratio <= 1.0) return 0.5 * M_PI * r * r * r * r;
  const double s = half_spacing(r, aspect_ratio);
  double area = 0, polar = 0;
  lens(r, 2 * s, area, polar);
  // Two disks about the midpoint (parallel axes), the lens counted once.
  return 2 * (0.5 * M_PI * r * r * r * r + M_PI * r * r * s * s) - polar;
}

std::vector<PowderParticle> place_powder(const PowderSpec& spec, const std::vector<double>& region, std::uint64_t seed) {
  spec.validate("particles");
  if (region.size() < 6 || region.size() % 2) throw Error("place_powder: the region needs three or more vertices");
  const double region_area = polygon_area(region);
  if (!(region_area > 0)) throw Error("place_powder: the region's vertices must run counter-clockwise");
  double lo_x = region[0], hi_x = region[0], lo_y = region[1], hi_y = region[1];
  for (std::size_t k = 0; k < region.size(); k += 2) {
    lo_x = std::min(lo_x, region[k]);
    hi_x = std::max(hi_x, region[k]);
    lo_y = std::min(lo_y, region[k + 1]);
    hi_y = std::max(hi_y, region[k + 1]);
  }
  // A cell grid over the region for the overlap test: cells as wide as the
  // longest particle, so only the 3 x 3 around a candidate can touch it.
  const double reach = spec.radius_max_m + half_spacing(spec.radius_max_m, spec.clump_aspect_ratio);
  const double cell = 2 * reach;
  const auto nx = static_cast<std::int64_t>((hi_x - lo_x) / cell) + 1;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  auto key = [&](double x, double y) {
    return static_cast<std::int64_t>((y - lo_y) / cell) * nx + static_cast<std::int64_t>((x - lo_x) / cell);
  };

  Rng rng(seed, 0x90dde5);
  std::vector<PowderParticle> out;
  std::vector<double> disk_x, disk_y, disk_r;  // every placed disk
  const double target = spec.solids_fraction * region_area;
  // The sizes first, until their area reaches the target, then placed the
  // largest first (as LIGGGHTS' insert/pack): drawing a size per try instead
  // let the small ones, which fit more easily, take the crowded end of a fill.
  std::vector<PowderParticle> sized;
  const bool clumps = spec.clump_aspect_ratio > 1.0;
  for (double drawn = 0; drawn < target;) {
    PowderParticle p;
    p.radius = rng.uniform(spec.radius_min_m, spec.radius_max_m);
    p.clump = clumps && rng.uniform() < spec.clump_fraction;
    drawn += particle_area_m2(p.radius, spec.clump_aspect_ratio, p.clump);
    sized.push_back(p);
  }
  std::stable_sort(sized.begin(), sized.end(), [&](const PowderParticle& a, const PowderParticle& b) {
    return particle_area_m2(a.radius, spec.clump_aspect_ratio, a.clump) >
           particle_area_m2(b.radius, spec.clump_aspect_ratio, b.clump);
  });
  double covered = 0;
  int misses = 0;
  for (std::size_t next = 0; next < sized.size();) {
    PowderParticle p = sized[next];
    p.angle_rad = rng.uniform(0.0, M_PI);
    p.x = rng.uniform(lo_x, hi_x);
    p.y = rng.uniform(lo_y, hi_y);
    const double s = p.clump ? half_spacing(p.radius, spec.clump_aspect_ratio) : 0.0;
    const double cx[2] = {p.x - s * std::cos(p.angle_rad), p.x + s * std::cos(p.angle_rad)};
    const double cy[2] = {p.y - s * std::sin(p.angle_rad), p.y + s * std::sin(p.angle_rad)};
    const int members = p.clump ? 2 : 1;
    bool ok = true;
    for (int m = 0; m < members && ok; ++m) {
      ok = inside_convex(region, cx[m], cy[m], p.radius);
      if (!ok) break;
      const std::int64_t gx = static_cast<std::int64_t>((cx[m] - lo_x) / cell), gy = static_cast<std::int64_t>((cy[m] - lo_y) / cell);
      for (std::int64_t dy = -1; dy <= 1 && ok; ++dy)
        for (std::int64_t dx = -1; dx <= 1 && ok; ++dx) {
          auto it = grid.find((gy + dy) * nx + gx + dx);
          if (it == grid.end()) continue;
          for (std::size_t d : it->second)
            if (std::hypot(disk_x[d] - cx[m], disk_y[d] - cy[m]) < disk_r[d] + p.radius) {
              ok = false;
              break;
            }
        }
    }
    if (!ok) {
      if (++misses > spec.max_attempts_per_particle)
        throw Error("particles: placed " + std::to_string(out.size()) + " particles covering " +
                    format_double(covered / region_area) + " of the fill region, short of its solids_fraction " +
                    format_double(spec.solids_fraction) + " after " + std::to_string(misses) +
                    " misses in a row; lower solids_fraction");
      continue;
    }
    misses = 0;
    ++next;
    for (int m = 0; m < members; ++m) {
      grid[key(cx[m], cy[m])].push_back(disk_x.size());
      disk_x.push_back(cx[m]);
      disk_y.push_back(cy[m]);
      disk_r.push_back(p.radius);
    }
    covered += particle_area_m2(p.radius, spec.clump_aspect_ratio, p.clump);
    out.push_back(p);
  }
  return out;
}

std::size_t add_powder(World& world, const std::vector<PowderParticle>& particles, const PowderSpec& spec,
                       double thickness_m, std::uint8_t group, std::uint64_t order_seed) {
  // Particle k's first disk id: the disks before it in the particles' own order.
  std::vector<std::int64_t> first_id(particles.size());
  std::int64_t next_id = static_cast<std::int64_t>(world.bodies.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    first_id[k] = next_id;
    next_id += particles[k].clump ? 2 : 1;
  }
  std::size_t added = 0;
  std::vector<std::size_t> order(particles.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  if (order_seed != 0) Rng(order_seed, 0x6f72646572 /* "order" */).shuffle(order);
  for (const std::size_t k : order) {
    const PowderParticle& p = particles[k];
    if (!p.clump) {
      world.bodies.add_disk(p.x, p.y, p.radius, spec.density_kg_m3, thickness_m, group, first_id[k]);
      ++added;
      continue;
    }
    const double s = half_spacing(p.radius, spec.clump_aspect_ratio);
    std::vector<std::size_t> members;
    for (int side : {-1, 1}) {
      members.push_back(world.bodies.add_disk(p.x + side * s * std::cos(p.angle_rad), p.y + side * s * std::sin(p.angle_rad),
                                              p.radius, spec.density_kg_m3, thickness_m, group,
                                              first_id[k] + (side < 0 ? 0 : 1)));
      ++added;
    }
    const double rho_t = spec.density_kg_m3 * thickness_m;
    world.add_clump(members, rho_t * particle_area_m2(p.radius, spec.clump_aspect_ratio, true),
                    rho_t * particle_polar_moment_m4(p.radius, spec.clump_aspect_ratio, true), p.x, p.y);
  }
  return added;
}

}  // namespace demcal::dem
