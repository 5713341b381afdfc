// Concrete aggregates: Walraven's gradation against the formula and the
// published counts, polygon geometry against closed forms, placement without
// overlap, and clumps with the polygon's mass and inertia.
#include <gtest/gtest.h>

#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem/aggregates.hpp"
#include "demcal/dem/concrete_specimen.hpp"

namespace {

using namespace demcal;
using namespace demcal::dem;

Polygon square(double half, double cx, double cy) {
  Polygon p;
  p.x = {cx - half, cx + half, cx + half, cx - half};
  p.y = {cy - half, cy - half, cy + half, cy + half};
  p.cx = cx;
  p.cy = cy;
  p.radius = half * std::sqrt(2.0);
  return p;
}

TEST(Walraven, FractionBelowTheLargestSizeIsAlmostTheCoarseFraction) {
  // At D0 = D_max: 1.065 - 0.053 - 0.012 - 0.0045 + 0.0025 = 0.998 of P_k.
  EXPECT_NEAR(walraven_fraction_below(0.015, 0.015, 0.75), 0.75 * 0.998, 1e-14);
  const double r = 5.0 / 15.0;
  EXPECT_NEAR(walraven_fraction_below(0.005, 0.015, 0.75),
              0.75 * (1.065 * std::sqrt(r) - 0.053 * std::pow(r, 4) - 0.012 * std::pow(r, 6) - 0.0045 * std::pow(r, 8) +
                      0.0025 * std::pow(r, 10)),
              1e-15);
}

TEST(Walraven, CountsOfThePublishedSpecimen) {
  // Su et al. 2021: 200 x 100 mm, 5-15 mm in five bins, P_k = 0.75 -> 59, 28, 15, 8, 4 aggregates.
  AggregateSpec spec;
  std::vector<SizeBin> bins = aggregate_counts(spec, 0.2 * 0.1);
  ASSERT_EQ(bins.size(), 5u);
  const int published[] = {59, 28, 15, 8, 4};
  for (int b = 0; b < 5; ++b) {
    EXPECT_EQ(bins[static_cast<std::size_t>(b)].count, published[b]) << "bin " << b;
    const SizeBin& bin = bins[static_cast<std::size_t>(b)];
    const double d = 0.5 * (bin.d_low_m + bin.d_high_m);
    EXPECT_NEAR(bin.count, 0.02 * bin.area_fraction / (M_PI * d * d / 4), 0.5);
  }
}

TEST(Polygon, SquareAgainstClosedForms) {
  Polygon p = square(1.0, 3.0, -2.0);  // side a = 2
  EXPECT_NEAR(p.area(), 4.0, 1e-14);
  double cx, cy;
  p.centroid(cx, cy);
  EXPECT_NEAR(cx, 3.0, 1e-14);
  EXPECT_NEAR(cy, -2.0, 1e-14);
  EXPECT_NEAR(p.polar_moment(), std::pow(2.0, 4) / 6.0, 1e-12);  // a^4 / 6 about the centroid
  EXPECT_TRUE(p.contains(3.5, -1.5));
  EXPECT_FALSE(p.contains(4.5, -2.0));
  EXPECT_NEAR(polygon_distance(p, square(1.0, 6.0, -2.0)), 1.0, 1e-14);
  EXPECT_NEAR(polygon_distance(p, square(1.0, 4.0, -1.0)), 0.0, 0.0);  // overlapping
}

TEST(Polygon, RandomPolygonsAreConvexAndOnTheirCircle) {
  Rng rng(5);
  for (int k = 0; k < 200; ++k) {
    const int sides = 4 + k % 3;
    Polygon p = random_polygon(sides, 0.01, 0.2, 0.3, rng);
    ASSERT_EQ(p.x.size(), static_cast<std::size_t>(sides));
    EXPECT_GE(p.area(), 0.35 * M_PI * 0.005 * 0.005);
    for (int i = 0; i < sides; ++i) {
      const int j = (i + 1) % sides, l = (i + 2) % sides;
      EXPECT_NEAR(std::hypot(p.x[static_cast<std::size_t>(i)] - 0.2, p.y[static_cast<std::size_t>(i)] - 0.3), 0.005, 1e-15);
      const double cross = (p.x[static_cast<std::size_t>(j)] - p.x[static_cast<std::size_t>(i)]) *
                               (p.y[static_cast<std::size_t>(l)] - p.y[static_cast<std::size_t>(j)]) -
                           (p.y[static_cast<std::size_t>(j)] - p.y[static_cast<std::size_t>(i)]) *
                               (p.x[static_cast<std::size_t>(l)] - p.x[static_cast<std::size_t>(j)]);
      EXPECT_GT(cross, 0.0) << "not convex";
    }
    EXPECT_TRUE(p.contains(0.2, 0.3));
  }
}

TEST(Placement, InsideTheSpecimenApartAndReproducible) {
  AggregateSpec spec;
  spec.min_gap_m = 0.001;
  AggregatePlacement a = place_aggregates(spec, 0.1, 0.2, 7);
  // More than the 59 + 28 + 15 + 8 + 4 circles: polygons inscribed in them fill less.
  EXPECT_GT(a.polygons.size(), 114u);
  EXPECT_EQ(a.requested, static_cast<int>(a.polygons.size()));
  for (std::size_t i = 0; i < a.polygons.size(); ++i) {
    const Polygon& p = a.polygons[i];
    for (std::size_t v = 0; v < p.x.size(); ++v) {
      EXPECT_GE(p.x[v], spec.min_gap_m - 1e-12);
      EXPECT_LE(p.x[v], 0.1 - spec.min_gap_m + 1e-12);
      EXPECT_GE(p.y[v], spec.min_gap_m - 1e-12);
      EXPECT_LE(p.y[v], 0.2 - spec.min_gap_m + 1e-12);
    }
    if (i > 0) {
      EXPECT_GE(a.polygons[i - 1].diameter_m, p.diameter_m);  // largest first
    }
    for (std::size_t j = 0; j < i; ++j) EXPECT_GE(polygon_distance(p, a.polygons[j]), spec.min_gap_m);
  }
  AggregatePlacement b = place_aggregates(spec, 0.1, 0.2, 7);
  EXPECT_EQ(a.polygons.back().x, b.polygons.back().x);
  AggregatePlacement c = place_aggregates(spec, 0.1, 0.2, 8);
  EXPECT_NE(a.polygons.back().x, c.polygons.back().x);
}

TEST(Placement, EachSizeBinFillsWalravensShareOfThePublishedSection) {
  // Su et al. 2021's 100 x 200 mm section, 5-15 mm, P_k = 0.75, 1 mm mortar gap.
  // Walraven: P_c = 0.287 over the range, 0.02-0.10 per bin. Goal (issue 14):
  // within 0.02 of it per bin; filling by polygon area stays within half the
  // largest polygon's area (0.0037 of the section), checked at 0.005.
  AggregateSpec spec;
  spec.min_gap_m = 0.001;
  for (std::uint64_t seed : {1u, 7u, 8u}) {
    AggregatePlacement a = place_aggregates(spec, 0.1, 0.2, seed);
    EXPECT_NEAR(a.target_area_fraction, 0.75 * (0.998 - walraven_fraction_below(0.005, 0.015, 1.0)), 1e-12);
    double sum = 0;
    for (const SizeBin& bin : a.bins) {
      EXPECT_NEAR(bin.placed_area_fraction, bin.area_fraction, 0.005)
          << "seed " << seed << ", bin " << bin.d_low_m * 1000 << "-" << bin.d_high_m * 1000 << " mm";
      sum += bin.placed_area_fraction;
    }
    EXPECT_NEAR(sum, a.area_fraction, 1e-12);
    EXPECT_NEAR(a.area_fraction, a.target_area_fraction, 0.01) << "seed " << seed;
  }
}

TEST(Placement, CountFillPlacesWalravensCircleEquivalentCounts) {
  // As Su et al. 2021 build their PFC2D concrete: 59, 28, 15, 8 and 4 polygons
  // on 100 x 200 mm. Inscribed in circles of the bins' diameters, they cover
  // less than Walraven's P_c: 4-6 vertices at random angles cover about 0.55
  // of their circle on average (0.152-0.159 of the section, against 0.288, on
  // the concrete scene's seeds 1-3), so 0.45-0.65 of P_c.
  AggregateSpec spec;
  spec.fill = AggregateFill::count;
  spec.min_gap_m = 0.001;
  const int published[] = {59, 28, 15, 8, 4};
  for (std::uint64_t seed : {1u, 7u}) {
    AggregatePlacement a = place_aggregates(spec, 0.1, 0.2, seed);
    ASSERT_EQ(a.bins.size(), 5u);
    for (int b = 0; b < 5; ++b) EXPECT_EQ(a.bins[static_cast<std::size_t>(b)].placed, published[b]) << "bin " << b;
    EXPECT_EQ(a.polygons.size(), 114u);
    EXPECT_GT(a.area_fraction, 0.45 * a.target_area_fraction) << "seed " << seed;
    EXPECT_LT(a.area_fraction, 0.65 * a.target_area_fraction) << "seed " << seed;
    // Area fill of the same seed holds more polygons for Walraven's area.
    spec.fill = AggregateFill::area;
    EXPECT_GT(place_aggregates(spec, 0.1, 0.2, seed).polygons.size(), 150u);
    spec.fill = AggregateFill::count;
  }
}

TEST(Placement, ImpossibleFractionSaysHowFarItGot) {
  AggregateSpec spec;
  spec.coarse_fraction = 1.0;
  spec.min_gap_m = 0.004;
  spec.max_attempts = 500;
  try {
    place_aggregates(spec, 0.05, 0.1, 1);
    FAIL() << "expected a placement failure";
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("aggregates: placed "), std::string::npos) << m;
    EXPECT_NE(m.find("% of the requested area"), std::string::npos) << m;
  }
}

TEST(ConcreteSpecimen, DisksInsideAPolygonFormOneClumpWithThePolygonsMassAndInertia) {
  World world;
  const double t = 1.0, rho = 2650;
  // A 3 x 3 grid of disks at spacing 2 mm around (0.05, 0.05) inside a 10 mm square; two mortar disks outside.
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) world.bodies.add_disk(0.05 + 0.002 * i, 0.05 + 0.002 * j, 0.001, 2000, t, 0);
  world.bodies.add_disk(0.07, 0.05, 0.001, 2000, t, 0);
  world.bodies.add_disk(0.03, 0.05, 0.001, 2000, t, 0);
  AggregatePlacement placement;
  placement.polygons = {square(0.005, 0.05, 0.05)};
  placement.requested = 1;
  AggregateSummary s = make_aggregate_clumps(world, placement, rho, t);
  EXPECT_EQ(s.clumps, 1);
  EXPECT_EQ(s.aggregate_disks, 9u);
  ASSERT_EQ(world.clumps().size(), 1u);
  const Clump& c = world.clumps()[0];
  EXPECT_NEAR(c.mass, rho * t * 0.01 * 0.01, 1e-12);
  EXPECT_NEAR(c.inertia, rho * t * std::pow(0.01, 4) / 6, 1e-15);
  EXPECT_NEAR(c.x, 0.05, 1e-15);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(world.bodies.group[i], kAggregateGroup);
  EXPECT_EQ(world.bodies.group[9], 0);
  EXPECT_EQ(world.bodies.clump[10], -1);
}

TEST(ConcreteSpecimen, APolygonHoldingNoDiskCentreTakesTheNearestFreeDisk) {
  World world;
  world.bodies.add_disk(0.0504, 0.05, 0.001, 2000, 1, 0);  // 0.4 mm off the small square's centre: outside it, inside its circle
  world.bodies.add_disk(0.0530, 0.05, 0.001, 2000, 1, 0);
  world.bodies.add_disk(0.0700, 0.05, 0.001, 2000, 1, 0);
  AggregatePlacement placement;
  placement.polygons = {square(0.0003, 0.05, 0.05), square(0.0003, 0.060, 0.05)};  // the second has no disk near
  placement.requested = 2;
  AggregateSummary s = make_aggregate_clumps(world, placement, 2650, 1);
  EXPECT_EQ(s.single_disk, 1);
  EXPECT_EQ(s.clumps, 1);
  EXPECT_EQ(s.without_disks, 1);
  EXPECT_EQ(world.bodies.group[0], kAggregateGroup);
  EXPECT_EQ(world.bodies.group[1], 0);
  ASSERT_EQ(world.clumps().size(), 1u);
  EXPECT_NEAR(world.clumps()[0].mass, 2650 * 0.0006 * 0.0006, 1e-9 * 2650 * 0.0006 * 0.0006);
}

}  // namespace
