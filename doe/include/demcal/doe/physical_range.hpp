#pragma once
// A design never leaves what its parameters can physically take without a
// word. A circumscribed CCD's axial points may leave the space's box (as
// Minitab's, and as published CCDs do), but not make a stress, stiffness,
// length, density or time negative, nor a ratio whose range is non-negative;
// with a scene, not leave the scene's declared bounds either.
#include <map>
#include <string>
#include <vector>

#include "demcal/core/parameter_space.hpp"
#include "demcal/core/table.hpp"

namespace demcal::doe {

// A parameter's physical bounds as a scene declares them.
struct PhysicalBounds {
  double low = -1e300, high = 1e300;
};

// One line per parameter whose design values leave its physical range: the
// worst value, the run it is in, and the bound it crosses. `design` holds the
// space's parameters in natural units (design_table with the space);
// `scene_bounds` may be empty or name only some parameters.
std::vector<std::string> physical_range_problems(const Table& design, const ParameterSpace& space,
                                                 const std::map<std::string, PhysicalBounds>& scene_bounds);

}  // namespace demcal::doe
