// The angle of repose fit on heaps built by hand: disks stacked in columns
// under a known surface line, each flank its own angle.
#include <gtest/gtest.h>

#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/dem/angle_of_repose.hpp"

using namespace demcal::dem;

namespace {

struct Heap {
  std::vector<double> x, y, r;
};

// Columns of disks of radius r, 2r wide, stacked on a base at y = 0 up to the
// surface h(x) = H - tan(left) |x| (x < 0) or H - tan(right) x (x > 0).
Heap stacked_heap(double r, double height_m, double left_deg, double right_deg) {
  Heap heap;
  const double tl = std::tan(left_deg * M_PI / 180), tr = std::tan(right_deg * M_PI / 180);
  for (double x = -height_m / tl - r; x <= height_m / tr + r; x += 2 * r) {
    const double h = height_m - (x < 0 ? tl * -x : tr * x);
    for (double y = r; y + r <= h + 1e-12; y += 2 * r) {
      heap.x.push_back(x);
      heap.y.push_back(y);
      heap.r.push_back(r);
    }
  }
  return heap;
}

}  // namespace

TEST(AngleOfRepose, AStackedHeapGivesItsSurfaceAngleOnEachFlank) {
  // 0.5 mm disks, a 60 mm heap: the staircase of column tops departs from the
  // line by at most one diameter, which moves a fitted slope by well under 0.5 degree.
  const double r = 0.5e-3;
  for (double angle : {25.0, 35.0, 47.8}) {
    const Heap heap = stacked_heap(r, 0.06, angle, angle);
    ReposeOptions options;
    options.bin_width_m = 2 * r;
    const ReposeFit fit = fit_angle_of_repose(heap.x, heap.y, heap.r, 0.0, options);
    EXPECT_NEAR(fit.left_deg, angle, 0.5) << angle;
    EXPECT_NEAR(fit.right_deg, angle, 0.5) << angle;
    EXPECT_NEAR(fit.mean_deg, angle, 0.5) << angle;
    EXPECT_NEAR(fit.height_m, 0.06, 2 * r);
    EXPECT_NEAR(fit.apex_x_m, 0.0, 3 * r);  // bins and columns are offset
    EXPECT_GT(fit.left_r2, 0.99);
    EXPECT_GE(fit.left_points, 10u);
  }
}

TEST(AngleOfRepose, FlanksAreFittedApartAndTheBaseHeightIsSubtracted) {
  const double r = 0.5e-3, base = 0.2;
  Heap heap = stacked_heap(r, 0.05, 30.0, 42.0);
  for (double& y : heap.y) y += base;
  // Run-out: a few disks lying on the base far out on the right stay below 10 % of the height.
  for (int k = 0; k < 5; ++k) {
    heap.x.push_back(0.12 + 0.01 * k);
    heap.y.push_back(base + r);
    heap.r.push_back(r);
  }
  ReposeOptions options;
  options.bin_width_m = 2 * r;
  const ReposeFit fit = fit_angle_of_repose(heap.x, heap.y, heap.r, base, options);
  EXPECT_NEAR(fit.left_deg, 30.0, 0.5);
  EXPECT_NEAR(fit.right_deg, 42.0, 0.5);
  EXPECT_NEAR(fit.mean_deg, 36.0, 0.5);
  // The lines meet near the apex, 50 mm up, and rise to the left and fall to the right.
  EXPECT_NEAR(fit.left_intercept_m, 0.05, 3 * r);
  EXPECT_NEAR(fit.right_intercept_m, 0.05, 3 * r);
  EXPECT_NEAR(fit.left_slope, std::tan(30.0 * M_PI / 180), 0.01);
  EXPECT_NEAR(fit.right_slope, -std::tan(42.0 * M_PI / 180), 0.01);
}

TEST(AngleOfRepose, AFlatLayerOrBadOptionsAreErrors) {
  const double r = 0.5e-3;
  Heap layer;
  for (int k = 0; k < 40; ++k) {
    layer.x.push_back(2 * r * k);
    layer.y.push_back(r);
    layer.r.push_back(r);
  }
  ReposeOptions options;
  options.bin_width_m = 2 * r;
  EXPECT_THROW(fit_angle_of_repose(layer.x, layer.y, layer.r, 0.0, options), demcal::Error);
  options.bin_width_m = 0;
  EXPECT_THROW(fit_angle_of_repose(layer.x, layer.y, layer.r, 0.0, options), demcal::Error);
  options.bin_width_m = 2 * r;
  options.low_fraction = 0.9;
  options.high_fraction = 0.1;
  EXPECT_THROW(fit_angle_of_repose(layer.x, layer.y, layer.r, 0.0, options), demcal::Error);
  EXPECT_THROW(fit_angle_of_repose({}, {}, {}, 0.0, ReposeOptions{2 * r}), demcal::Error);
}

// A baffle lift's pile: a plateau against the back wall at x = 0, then one
// slope down to the floor. fit_slope fits the slope alone (the plateau sits
// above 90 % of the height), and says when there are too few points.
TEST(AngleOfRepose, ASlopeLeaningOnAWallGivesItsAngle) {
  const double r = 0.5e-3, height = 0.04, plateau = 0.01;
  for (double angle : {30.0, 39.1, 55.0}) {
    const double t = std::tan(angle * M_PI / 180);
    std::vector<double> x, y, radius;
    for (double xc = r; xc <= plateau + height / t; xc += 2 * r) {
      const double h = xc <= plateau ? height : height - t * (xc - plateau);
      for (double yc = r; yc + r <= h + 1e-12; yc += 2 * r) {
        x.push_back(xc);
        y.push_back(yc);
        radius.push_back(r);
      }
    }
    ReposeOptions options;
    options.bin_width_m = 2 * r;
    const SurfaceProfile profile = surface_profile(x, y, radius, 0.0, options.bin_width_m);
    EXPECT_NEAR(profile.height_m[profile.highest], height, 2 * r);
    EXPECT_NEAR(profile.x_m[profile.highest], r, r) << "the first of the highest bins: at the wall";
    const SlopeFit fit = fit_slope(profile, options, "test slope");
    EXPECT_NEAR(fit.deg, angle, 0.5) << angle;
    EXPECT_LT(fit.slope, 0);
    EXPECT_GT(fit.r2, 0.99);
    EXPECT_GE(fit.points, 10u);
  }
  // Two columns: no slope to fit.
  const SurfaceProfile short_pile = surface_profile({r, 3 * r}, {r, r}, {r, r}, 0.0, 2 * r);
  ReposeOptions options;
  options.bin_width_m = 2 * r;
  try {
    fit_slope(short_pile, options, "slice 1");
    FAIL() << "a flat two-bin pile gave a slope";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("slice 1: "), std::string::npos) << e.what();
  }
}
