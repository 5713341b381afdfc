#pragma once
// The free surface's angle in a rotating drum's cross-section (x across, z
// up, the axis along y): the highest sphere top in bins of `bin_m` along x,
// and a least-squares line through the middle `surface_fraction` of the bins
// that hold spheres (the ends climb the shell); atan of its slope's
// magnitude, in degrees. An Error when too few bins are left to fit.
#include <vector>

namespace demcal::dem3d {

double drum_surface_angle_deg(const std::vector<double>& x_m, const std::vector<double>& z_m,
                              const std::vector<double>& radius_m, double drum_radius_m, double bin_m,
                              double surface_fraction);

}  // namespace demcal::dem3d
