#include "demcal/dem/aggregates.hpp"

#include <algorithm>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/rng.hpp"

namespace demcal::dem {

void AggregateSpec::validate(const std::string& where) const {
  if (!(d_min_m > 0 && d_max_m > d_min_m)) throw Error(where + ": size range needs 0 < d_min < d_max");
  if (bins < 1) throw Error(where + ": bins must be at least 1");
  if (!(coarse_fraction > 0 && coarse_fraction <= 1)) throw Error(where + ": coarse_fraction (P_k) must lie in (0, 1]");
  if (sides_min < 3 || sides_max < sides_min) throw Error(where + ": sides must be [min, max] with 3 <= min <= max");
  if (min_gap_m < 0) throw Error(where + ": min_gap_m must be >= 0");
  if (!(density_kg_m3 > 0)) throw Error(where + ": density_kg_m3 must be positive");
  if (max_attempts < 1) throw Error(where + ": max_attempts must be at least 1");
}

double walraven_fraction_below(double d0_m, double d_max_m, double coarse_fraction) {
  const double r = d0_m / d_max_m;
  return coarse_fraction * (1.065 * std::sqrt(r) - 0.053 * std::pow(r, 4) - 0.012 * std::pow(r, 6) -
                            0.0045 * std::pow(r, 8) + 0.0025 * std::pow(r, 10));
}

std::vector<SizeBin> aggregate_counts(const AggregateSpec& spec, double area_m2) {
  std::vector<SizeBin> bins;
  const double width = (spec.d_max_m - spec.d_min_m) / spec.bins;
  for (int b = 0; b < spec.bins; ++b) {
    SizeBin bin;
    bin.d_low_m = spec.d_min_m + b * width;
    bin.d_high_m = bin.d_low_m + width;
    bin.area_fraction = walraven_fraction_below(bin.d_high_m, spec.d_max_m, spec.coarse_fraction) -
                        walraven_fraction_below(bin.d_low_m, spec.d_max_m, spec.coarse_fraction);
    const double d_mean = 0.5 * (bin.d_low_m + bin.d_high_m);
    bin.count = static_cast<int>(std::lround(area_m2 * bin.area_fraction / (M_PI * d_mean * d_mean / 4)));
    bins.push_back(bin);
  }
  return bins;
}

double Polygon::area() const {
  double a = 0;
  for (std::size_t i = 0, n = x.size(); i < n; ++i) a += x[i] * y[(i + 1) % n] - x[(i + 1) % n] * y[i];
  return 0.5 * a;
}

void Polygon::centroid(double& px, double& py) const {
  double a = 0, sx = 0, sy = 0;
  for (std::size_t i = 0, n = x.size(); i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double cross = x[i] * y[j] - x[j] * y[i];
    a += cross;
    sx += (x[i] + x[j]) * cross;
    sy += (y[i] + y[j]) * cross;
  }
  px = sx / (3 * a);
  py = sy / (3 * a);
}

double Polygon::polar_moment() const {
  // About the origin, then moved to the centroid (parallel axis).
  double j0 = 0;
  for (std::size_t i = 0, n = x.size(); i < n; ++i) {
    const std::size_t k = (i + 1) % n;
    const double cross = x[i] * y[k] - x[k] * y[i];
    j0 += cross * (x[i] * x[i] + x[i] * x[k] + x[k] * x[k] + y[i] * y[i] + y[i] * y[k] + y[k] * y[k]);
  }
  j0 /= 12.0;
  double px, py;
  centroid(px, py);
  return j0 - area() * (px * px + py * py);
}

bool Polygon::contains(double px, double py) const {
  // Counter-clockwise convex polygon: inside when left of every edge.
  for (std::size_t i = 0, n = x.size(); i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if ((x[j] - x[i]) * (py - y[i]) - (y[j] - y[i]) * (px - x[i]) < 0) return false;
  }
  return true;
}

Polygon random_polygon(int sides, double diameter_m, double cx, double cy, Rng& rng) {
  const double r = 0.5 * diameter_m;
  for (;;) {
    std::vector<double> angles(static_cast<std::size_t>(sides));
    for (double& a : angles) a = rng.uniform(0.0, 2 * M_PI);
    std::sort(angles.begin(), angles.end());
    double largest_gap = angles.front() + 2 * M_PI - angles.back();
    for (std::size_t k = 1; k < angles.size(); ++k) largest_gap = std::max(largest_gap, angles[k] - angles[k - 1]);
    if (largest_gap >= M_PI) continue;  // the centre would fall outside
    Polygon p;
    for (double a : angles) {
      p.x.push_back(cx + r * std::cos(a));
      p.y.push_back(cy + r * std::sin(a));
    }
    if (p.area() < 0.35 * M_PI * r * r) continue;  // a sliver
    p.diameter_m = diameter_m;
    p.cx = cx;
    p.cy = cy;
    p.radius = r;
    return p;
  }
}

namespace {

double point_segment_distance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (ax + t * dx), py - (ay + t * dy));
}

// True when an edge normal of `a` separates the two polygons (separating axis theorem).
bool separated_by_edges_of(const Polygon& a, const Polygon& b) {
  for (std::size_t i = 0, n = a.x.size(); i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double nx = a.y[j] - a.y[i], ny = a.x[i] - a.x[j];  // outward for counter-clockwise
    double max_a = -INFINITY, min_b = INFINITY;
    for (std::size_t k = 0; k < a.x.size(); ++k) max_a = std::max(max_a, nx * a.x[k] + ny * a.y[k]);
    for (std::size_t k = 0; k < b.x.size(); ++k) min_b = std::min(min_b, nx * b.x[k] + ny * b.y[k]);
    if (min_b > max_a) return true;
  }
  return false;
}

}  // namespace

double polygon_distance(const Polygon& a, const Polygon& b) {
  if (!separated_by_edges_of(a, b) && !separated_by_edges_of(b, a)) return 0.0;
  double d = INFINITY;
  for (std::size_t i = 0, n = a.x.size(); i < n; ++i)
    for (std::size_t k = 0, m = b.x.size(); k < m; ++k) {
      d = std::min(d, point_segment_distance(a.x[i], a.y[i], b.x[k], b.y[k], b.x[(k + 1) % m], b.y[(k + 1) % m]));
      d = std::min(d, point_segment_distance(b.x[k], b.y[k], a.x[i], a.y[i], a.x[(i + 1) % n], a.y[(i + 1) % n]));
    }
  return d;
}

AggregatePlacement place_aggregates(const AggregateSpec& spec, double width_m, double height_m, std::uint64_t seed) {
  spec.validate("aggregates");
  AggregatePlacement placement;
  const double section_m2 = width_m * height_m;
  placement.bins = aggregate_counts(spec, section_m2);
  Rng rng(seed, 0xa66e /* "agg" */);
  // Shapes drawn at the origin, bin by bin, diameters uniform in the bin.
  struct Shape {
    Polygon polygon;
    std::size_t bin;
  };
  std::vector<Shape> shapes;
  double requested_area = 0;
  for (std::size_t b = 0; b < placement.bins.size(); ++b) {
    SizeBin& bin = placement.bins[b];
    placement.target_area_fraction += bin.area_fraction;
    const double target_m2 = bin.area_fraction * section_m2;
    double drawn_m2 = 0;
    for (int drawn = 0;; ++drawn) {
      if (spec.fill == AggregateFill::count && drawn == bin.count) break;
      const int sides = spec.sides_min + static_cast<int>(rng.below(static_cast<std::uint64_t>(spec.sides_max - spec.sides_min + 1)));
      Polygon p = random_polygon(sides, rng.uniform(bin.d_low_m, bin.d_high_m), 0.0, 0.0, rng);
      const double a = p.area();
      // Fill area: stop where the next one would overshoot by more than it fills.
      if (spec.fill == AggregateFill::area && drawn_m2 + 0.5 * a > target_m2) break;
      drawn_m2 += a;
      shapes.push_back({std::move(p), b});
    }
    requested_area += drawn_m2;
  }
  std::stable_sort(shapes.begin(), shapes.end(),
                   [](const Shape& a, const Shape& b) { return a.polygon.diameter_m > b.polygon.diameter_m; });
  placement.requested = static_cast<int>(shapes.size());
  double placed_area = 0;
  const double gap = spec.min_gap_m;
  for (const Shape& shape : shapes) {
    const double r = shape.polygon.radius;
    bool placed = false;
    for (int attempt = 0; attempt < spec.max_attempts && !placed; ++attempt) {
      if (width_m <= 2 * (r + gap) || height_m <= 2 * (r + gap)) break;
      const double cx = rng.uniform(r + gap, width_m - r - gap), cy = rng.uniform(r + gap, height_m - r - gap);
      Polygon p = shape.polygon;
      for (double& x : p.x) x += cx;
      for (double& y : p.y) y += cy;
      p.cx = cx;
      p.cy = cy;
      bool clear = true;
      for (const Polygon& other : placement.polygons) {
        if (std::hypot(cx - other.cx, cy - other.cy) >= r + other.radius + gap) continue;  // bounding circles apart
        if (polygon_distance(p, other) < gap) {
          clear = false;
          break;
        }
      }
      if (!clear) continue;
      const double a = p.area();
      placement.polygons.push_back(std::move(p));
      placed_area += a;
      placement.bins[shape.bin].placed += 1;
      placement.bins[shape.bin].placed_area_fraction += a / section_m2;
      placed = true;
    }
    if (!placed)
      throw Error("aggregates: placed " + std::to_string(placement.polygons.size()) + " of " +
                  std::to_string(placement.requested) + " (" + format_double(std::round(1000 * placed_area / requested_area) / 10) +
                  " % of the requested area) before one of diameter " + format_double(shape.polygon.diameter_m * 1000) +
                  " mm found no free spot in " + std::to_string(spec.max_attempts) +
                  " tries; lower coarse_fraction or min_gap_m, or enlarge the specimen");
  }
  placement.area_fraction = placed_area / section_m2;
  return placement;
}

}  // namespace demcal::dem
