#pragma once
// The angle of repose of a settled 3D heap on a round platform, from vertical
// sections through the platform's axis: each section is a slab of spheres
// around a plane at azimuth k pi / n, seen as a 2D profile (the distance
// along the plane against the height) and fitted as the 2D heap is, both
// flanks between 10 and 90 % of the section's height (angle_of_repose.hpp).
// The heap's angle is the mean over the 2 n flanks, its scatter their SD; the
// height-based (fixed-base) angle is atan(height / platform radius).
#include <cstddef>
#include <vector>

#include "demcal/dem/angle_of_repose.hpp"

namespace demcal::dem3d {

struct HeapSectionOptions {
  std::size_t sections = 8;     // planes through the axis, 180 / sections degrees apart
  double slab_width_m = 0;      // > 0: spheres whose centre lies within half of it of the plane
  dem::ReposeOptions profile;   // the 2D fit of each section (its bin width > 0)
};

struct HeapSectionFit {
  double mean_deg = 0, sd_deg = 0;  // over every flank of every section
  double height_m = 0;              // the highest section's surface above the platform
  std::vector<double> flank_deg;    // section k's two flanks at 2 k and 2 k + 1
  std::vector<dem::ReposeFit> sections;
};

// Spheres at (x, y, z) with radii r on a platform at height base_z_m centred on
// the z axis; only the spheres given count. An Error when a section has too
// few surface points on a flank.
HeapSectionFit fit_heap_sections(const std::vector<double>& x_m, const std::vector<double>& y_m,
                                 const std::vector<double>& z_m, const std::vector<double>& radius_m, double base_z_m,
                                 const HeapSectionOptions& options);

}  // namespace demcal::dem3d
