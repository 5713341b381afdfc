// A slope section: bedrock below a profile, zones of smaller disks on it (slope_specimen.hpp).
#include "demcal/dem/slope_specimen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/genesis.hpp"

namespace demcal::dem {
namespace {

// Boxes are packed by radius expansion (genesis.hpp), which wants at least 6 radii across.
constexpr double kRadiiAcross = 6.0;

// Kept disks by cell, to find the ones a new disk would overlap.
class DiskGrid {
 public:
  explicit DiskGrid(double cell_m) : cell_m_(cell_m) {}
  void insert(std::size_t k, double x, double y) { cells_[key(cell(x), cell(y))].push_back(k); }
  // Whether a disk at (x, y) of radius r overlaps a disk already inserted (cells no smaller than two radii).
  bool overlaps(const SlopeSpecimen& s, double x, double y, double r) const {
    const long cx = cell(x), cy = cell(y);
    for (long i = cx - 1; i <= cx + 1; ++i)
      for (long j = cy - 1; j <= cy + 1; ++j) {
        const auto found = cells_.find(key(i, j));
        if (found == cells_.end()) continue;
        for (std::size_t k : found->second)
          if (std::hypot(s.x[k] - x, s.y[k] - y) < s.radius[k] + r) return true;
      }
    return false;
  }

 private:
  long cell(double v) const { return static_cast<long>(std::floor(v / cell_m_)); }
  static long long key(long i, long j) { return (static_cast<long long>(i) << 32) ^ static_cast<long long>(j & 0xffffffff); }
  double cell_m_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

Specimen pack_box(const SlopePart& part, double width_m, double height_m, double thickness_m, std::uint64_t seed,
                  const std::string& cache_dir) {
  SpecimenSpec box;
  box.width_m = width_m;
  box.height_m = height_m;
  box.thickness_m = thickness_m;
  box.porosity = part.porosity;
  box.radius_min_m = part.radius_min_m;
  box.radius_max_m = part.radius_max_m;
  box.density_kg_m3 = part.density_kg_m3;
  box.seed = seed;
  return cached_specimen(box, cache_dir);
}

}  // namespace

double Profile::at(double x_m) const {
  if (x_m <= x.front()) return y.front();
  if (x_m >= x.back()) return y.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), x_m) - x.begin());
  const double f = (x_m - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + f * (y[k] - y[k - 1]);
}

double Profile::min_y(double from_x_m, double to_x_m) const {
  double low = std::min(at(from_x_m), at(to_x_m));
  for (std::size_t k = 0; k < x.size(); ++k)
    if (x[k] > from_x_m && x[k] < to_x_m) low = std::min(low, y[k]);
  return low;
}

double Profile::max_y(double from_x_m, double to_x_m) const {
  double high = std::max(at(from_x_m), at(to_x_m));
  for (std::size_t k = 0; k < x.size(); ++k)
    if (x[k] > from_x_m && x[k] < to_x_m) high = std::max(high, y[k]);
  return high;
}

double Profile::area_above(double base_y_m) const {
  double area = 0;
  for (std::size_t k = 1; k < x.size(); ++k)
    area += 0.5 * (x[k] - x[k - 1]) * (std::max(0.0, y[k - 1] - base_y_m) + std::max(0.0, y[k] - base_y_m));
  return area;
}

void Profile::validate(const std::string& where) const {
  if (x.size() < 2) throw Error(where + ": needs at least 2 points [x_m, y_m]");
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!std::isfinite(x[k]) || !std::isfinite(y[k]))
      throw Error(where + "[" + std::to_string(k) + "]: not a finite number");
    if (k > 0 && !(x[k] > x[k - 1]))
      throw Error(where + "[" + std::to_string(k) + "]: x " + format_double(x[k]) + " m does not exceed the point before (" +
                  format_double(x[k - 1]) + " m): a profile runs left to right and cannot turn back on itself");
  }
}

void SlopeSpec::validate(const std::string& where) const {
  if (!(width_m > 0 && height_m > 0 && thickness_m > 0))
    throw Error(where + ": width_m, height_m and thickness_m must be positive");
  auto part_ok = [&](const SlopePart& p, const std::string& w) {
    if (!(p.radius_min_m > 0 && p.radius_max_m >= p.radius_min_m))
      throw Error(w + ": radius_min_m must be positive and radius_max_m at least radius_min_m");
    if (!(p.porosity > 0.05 && p.porosity < 0.5)) throw Error(w + ".porosity must lie in (0.05, 0.5)");
    if (!(p.density_kg_m3 > 0)) throw Error(w + ".density_kg_m3 must be positive");
  };
  part_ok(bedrock, where + ".bedrock");
  bedrock_surface.validate(where + ".bedrock.surface");
  if (std::abs(bedrock_surface.x.front()) > 1e-9 || std::abs(bedrock_surface.x.back() - width_m) > 1e-9)
    throw Error(where + ".bedrock.surface: must run from x = 0 to x = width_m (" + format_double(width_m) + " m)");
  for (std::size_t k = 0; k < bedrock_surface.x.size(); ++k)
    if (!(bedrock_surface.y[k] >= kRadiiAcross * bedrock.radius_max_m && bedrock_surface.y[k] <= height_m))
      throw Error(where + ".bedrock.surface[" + std::to_string(k) + "]: y " + format_double(bedrock_surface.y[k]) +
                  " m must lie between 6 bedrock radii (" + format_double(kRadiiAcross * bedrock.radius_max_m) +
                  " m) and height_m (" + format_double(height_m) + " m)");
  if (!(column_width_m > 0)) throw Error(where + ".column_width_m must be positive");
  for (std::size_t z = 0; z < zones.size(); ++z) {
    const std::string w = where + ".zones[" + std::to_string(z) + "]";
    part_ok(zones[z].part, w);
    zones[z].top.validate(w + ".top");
    const Profile& top = zones[z].top;
    if (top.x.front() < 0 || top.x.back() > width_m)
      throw Error(w + ".top: runs outside the model (x from 0 to " + format_double(width_m) + " m)");
    if (top.x.back() - top.x.front() < kRadiiAcross * zones[z].part.radius_max_m)
      throw Error(w + ".top: spans less than 6 of the zone's radii");
    bool room = false;
    for (std::size_t k = 0; k < top.x.size(); ++k) {
      if (top.y[k] > height_m)
        throw Error(w + ".top[" + std::to_string(k) + "]: y " + format_double(top.y[k]) + " m is above height_m (" +
                    format_double(height_m) + " m)");
    }
    // Room: somewhere the top stands above what lies under it by at least one of the zone's diameters.
    const int samples = 200;
    for (int q = 0; q <= samples && !room; ++q) {
      const double xq = top.x.front() + (top.x.back() - top.x.front()) * q / samples;
      room = top.at(xq) - top_below_zone(z, xq) >= 2 * zones[z].part.radius_max_m;
    }
    if (!room)
      throw Error(w + ".top: lies nowhere a diameter above the bedrock and the zones before it, so the zone is empty");
  }
}

double SlopeSpec::top_below_zone(std::size_t z, double x_m) const {
  double top = bedrock_surface.at(x_m);
  for (std::size_t j = 0; j < z && j < zones.size(); ++j)
    if (zones[j].top.covers(x_m)) top = std::max(top, zones[j].top.at(x_m));
  return top;
}

SlopeSpecimen build_slope_specimen(const SlopeSpec& spec, const std::string& cache_dir) {
  SlopeSpecimen s;
  s.width_m = spec.width_m;
  s.height_m = spec.height_m;
  s.thickness_m = spec.thickness_m;
  s.geometry = spec;
  double r_largest = spec.bedrock.radius_max_m;
  for (const SlopeZone& z : spec.zones) r_largest = std::max(r_largest, z.part.radius_max_m);
  DiskGrid grid(2 * r_largest);
  // A part's disks keep the overlaps of their packing; only a later part's must not overlap them.
  auto keep = [&](double x, double y, double r, std::uint8_t part) {
    s.x.push_back(x);
    s.y.push_back(y);
    s.radius.push_back(r);
    s.part.push_back(part);
  };

  // The bedrock: one box up to its highest point, cut to the disks wholly below the surface (whose hollows the
  // zone on it fills), so the surface is the bedrock's top and no disk stands above it.
  const double bedrock_top = spec.bedrock_surface.max_y(0, spec.width_m);
  const Specimen bed = pack_box(spec.bedrock, spec.width_m, bedrock_top, spec.thickness_m, spec.seed, cache_dir);
  for (std::size_t i = 0; i < bed.size(); ++i)
    if (bed.y[i] + bed.radius[i] <= spec.bedrock_surface.at(bed.x[i])) keep(bed.x[i], bed.y[i], bed.radius[i], 0);
  s.part_names.push_back(spec.bedrock.name);
  s.part_density_kg_m3.push_back(spec.bedrock.density_kg_m3);
  s.part_porosity.push_back(spec.bedrock.porosity);
  s.part_area_m2.push_back(spec.bedrock_surface.area_above(0));
  s.part_disks.push_back(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) grid.insert(k, s.x[k], s.y[k]);

  // Each zone in columns: a box from a little below what lies under the column (the lower part's disks leave
  // hollows up to a diameter deep) to the zone's top, cut to the zone and to no overlap with what is there.
  double r_below = spec.bedrock.radius_max_m;
  for (std::size_t z = 0; z < spec.zones.size(); ++z) {
    const SlopeZone& zone = spec.zones[z];
    const Profile& top = zone.top;
    auto under = [&](double x) { return spec.top_below_zone(z, x); };
    const double r_max = zone.part.radius_max_m, span = top.x.back() - top.x.front();
    const std::size_t columns =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(span / std::max(spec.column_width_m, kRadiiAcross * r_max))));
    const double column_m = span / static_cast<double>(columns);
    const std::size_t before = s.size();
    double area = 0;
    for (std::size_t c = 0; c < columns; ++c) {
      const double xa = top.x.front() + column_m * static_cast<double>(c), xb = c + 1 == columns ? top.x.back() : xa + column_m;
      double low = std::numeric_limits<double>::infinity();
      const int samples = 50;
      for (int q = 0; q <= samples; ++q) low = std::min(low, under(xa + (xb - xa) * q / samples));
      low = std::max(0.0, low - 2 * r_below);
      const double high = std::max(top.max_y(xa, xb), low + kRadiiAcross * r_max);
      const std::uint64_t seed = spec.seed + 1000003ULL * (z + 1) + 7919ULL * c;
      const Specimen box = pack_box(zone.part, xb - xa, high - low, spec.thickness_m, seed, cache_dir);
      for (std::size_t i = 0; i < box.size(); ++i) {
        const double x = xa + box.x[i], y = low + box.y[i], r = box.radius[i];
        if (y + r > top.at(x) || y < under(x) - 2 * r_below) continue;
        if (grid.overlaps(s, x, y, r)) continue;
        keep(x, y, r, static_cast<std::uint8_t>(z + 1));
      }
      // The zone's own area in this column, by the trapezoid rule on a fine sampling.
      const int steps = 400;
      for (int q = 0; q < steps; ++q) {
        const double x0 = xa + (xb - xa) * q / steps, x1 = xa + (xb - xa) * (q + 1) / steps;
        area += 0.5 * (x1 - x0) * (std::max(0.0, top.at(x0) - under(x0)) + std::max(0.0, top.at(x1) - under(x1)));
      }
    }
    s.part_names.push_back(zone.part.name);
    s.part_density_kg_m3.push_back(zone.part.density_kg_m3);
    s.part_porosity.push_back(zone.part.porosity);
    s.part_area_m2.push_back(area);
    s.part_disks.push_back(s.size() - before);
    for (std::size_t k = before; k < s.size(); ++k) grid.insert(k, s.x[k], s.y[k]);
    r_below = std::max(r_below, r_max);
  }
  return s;
}

}  // namespace demcal::dem
