#pragma once
// The angle of repose of a settled 2D heap, as DEM practice measures it
// (docs/explanation/heap_test.md): the surface profile is the highest particle top
// (y + r) in bins across the heap; each flank's points between 10 % and 90 %
// of the heap's height (dropping the rounded apex and the run-out toe) get a
// least-squares line, and the angle is atan |slope|, the mean of both flanks.
#include <cstddef>
#include <string>
#include <vector>

namespace demcal::dem {

struct ReposeFit {
  double left_deg = 0, right_deg = 0, mean_deg = 0;  // flank angles and their mean, degrees
  double height_m = 0;                              // highest surface point above the base
  double apex_x_m = 0;                              // x of the highest bin's centre
  std::size_t left_points = 0, right_points = 0;    // surface points each line was fitted to
  double left_r2 = 0, right_r2 = 0;                 // each line's coefficient of determination
  // Each line as height = intercept + slope x (m above the base; x in m).
  double left_slope = 0, left_intercept_m = 0, right_slope = 0, right_intercept_m = 0;
  std::vector<double> profile_x_m, profile_height_m;  // the surface profile (bin centres, heights)
};

struct ReposeOptions {
  double bin_width_m = 0;         // > 0; 1-2 particle diameters
  double low_fraction = 0.1;      // flank points kept between these fractions of the height
  double high_fraction = 0.9;
  std::size_t min_points = 3;     // per flank, else the heap is too small for the bins (an Error)
};

// The surface of a pile: in bins of bin_width_m along x from the leftmost
// particle's edge, each bin's highest particle top (y + r) above base_y_m; a
// particle counts in the bin of its centre, and empty bins are left out.
struct SurfaceProfile {
  std::vector<double> x_m, height_m;  // bin centres and heights, left to right
  std::size_t highest = 0;            // the first of the highest bins
};
SurfaceProfile surface_profile(const std::vector<double>& x_m, const std::vector<double>& y_m,
                               const std::vector<double>& radius_m, double base_y_m, double bin_width_m);

// One slope of a profile (a baffle-lift pile's, which leans on a wall): the
// least-squares line through the profile's points between low_fraction and
// high_fraction of its highest point; an Error naming `what` when fewer than
// options.min_points lie there.
struct SlopeFit {
  double deg = 0;                       // atan |slope|
  double slope = 0, intercept_m = 0, r2 = 0;
  std::size_t points = 0;
};
SlopeFit fit_slope(const SurfaceProfile& profile, const ReposeOptions& options, const std::string& what);

// Disks at (x, y) with radii r on a base at height base_y_m; only the disks
// given count (a test passes the ones on the heap, not those still in a
// funnel). Throws a demcal::Error when a flank has too few points.
ReposeFit fit_angle_of_repose(const std::vector<double>& x_m, const std::vector<double>& y_m,
                              const std::vector<double>& radius_m, double base_y_m, const ReposeOptions& options);

}  // namespace demcal::dem
