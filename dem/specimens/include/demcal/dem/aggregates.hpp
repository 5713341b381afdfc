#pragma once
// Concrete aggregates in 2D: how many of each size (Walraven's gradation),
// their shapes (random convex polygons) and where they go (take and place,
// largest first, without overlap and with a mortar gap).
#include <cstdint>
#include <string>
#include <vector>

namespace demcal {
class Rng;
}

namespace demcal::dem {

// How many polygons each size bin gets.
//  - area: polygons are drawn until their own area meets the bin's Walraven
//    share P_c, so the section holds Walraven's aggregate area.
//  - count: the bin's circle-equivalent count (its share over the area of a
//    circle of the bin's mean diameter), as Su et al. 2021 build their PFC2D
//    concrete (59, 28, 15, 8 and 4 aggregates on 200 x 100 mm); polygons
//    inscribed in those circles cover less than P_c (about 0.15 against 0.29).
enum class AggregateFill { area, count };

struct AggregateSpec {
  AggregateFill fill = AggregateFill::area;
  double d_min_m = 0.005, d_max_m = 0.015;  // sieve sizes bounding the gradation
  int bins = 5;                             // equal-width size bins between them
  double coarse_fraction = 0.75;            // P_k, aggregate volume fraction of the concrete
  int sides_min = 4, sides_max = 6;         // polygon side count, uniform
  double min_gap_m = 0.0;                   // mortar gap between aggregates and to the boundary
  double density_kg_m3 = 2650;
  int max_attempts = 20000;                 // random positions tried per aggregate
  void validate(const std::string& where) const;
};

// Walraven's 2D gradation: the probability that a point of the section lies
// in an aggregate of diameter below D0,
//   P_c = P_k [1.065 r^0.5 - 0.053 r^4 - 0.012 r^6 - 0.0045 r^8 + 0.0025 r^10], r = D0 / D_max.
double walraven_fraction_below(double d0_m, double d_max_m, double coarse_fraction);

struct SizeBin {
  double d_low_m = 0, d_high_m = 0;
  int count = 0;            // circle-equivalent count for the section (what Su et al. 2021 publish)
  double area_fraction = 0; // P_c(d_high) - P_c(d_low), the share an area fill meets
  int placed = 0;                  // polygons placed in this bin
  double placed_area_fraction = 0; // their area / section area
};

// Aggregates per bin for a section of `area_m2`: area fraction of the bin
// over the area of a circle of the bin's mean diameter, rounded. Polygons
// inscribed in those circles fill less, so an area fill meets each bin's
// area instead and places more of them; a count fill places these counts.
std::vector<SizeBin> aggregate_counts(const AggregateSpec& spec, double area_m2);

struct Polygon {
  std::vector<double> x, y;  // vertices, counter-clockwise
  double diameter_m = 0;     // of the circle the vertices lie on
  double area() const;
  void centroid(double& cx, double& cy) const;
  // Polar moment of area about the centroid (m^4): inertia = density t this.
  double polar_moment() const;
  bool contains(double px, double py) const;
  // Bounding circle (the vertices' circle).
  double cx = 0, cy = 0, radius = 0;
};

// A convex polygon with `sides` vertices at random angles on a circle of
// `diameter` centred at (cx, cy); angular gaps are kept below pi so the centre
// lies inside and slivers are redrawn (area at least 35 % of the circle's).
Polygon random_polygon(int sides, double diameter_m, double cx, double cy, Rng& rng);

// Smallest distance between two convex polygons (0 when they overlap).
double polygon_distance(const Polygon& a, const Polygon& b);

struct AggregatePlacement {
  std::vector<Polygon> polygons;  // largest first
  std::vector<SizeBin> bins;
  int requested = 0;
  double area_fraction = 0;         // placed polygon area / section area
  double target_area_fraction = 0;  // Walraven's P_c over the size range
};

// Draws polygons per size bin, until their area meets the bin's Walraven share
// (fill area: the last one kept while it brings the bin closer to it) or the
// bin's circle-equivalent count (fill count), then places them
// in [0, width] x [0, height], largest first, at random positions, each at
// least min_gap from the boundary and from every other polygon (bounding
// circles first, then the exact polygon distance). Throws, naming the
// fraction placed, when one cannot be placed.
AggregatePlacement place_aggregates(const AggregateSpec& spec, double width_m, double height_m, std::uint64_t seed);

}  // namespace demcal::dem
