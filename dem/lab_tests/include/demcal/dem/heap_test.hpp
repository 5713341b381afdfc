#pragma once
// Heap test (the fixed-funnel angle of repose, 2D): a funnel filled with a
// powder opens onto a raised base; the particles that run off the base fall
// to a catch floor below it; once the heap has settled (kinetic energy below
// a set share of the potential), its angle of repose is fitted to both flanks
// (angle_of_repose.hpp). docs/explanation/heap_test.md says why a funnel and not a lifted
// cylinder, and how the geometry is chosen.
//
//   "particles": {"radius_min_m", "radius_max_m", "density_kg_m3", "thickness_m" (default: the mean diameter),
//                 "clump_aspect_ratio" (1: disks), "clump_fraction" (default 1)},
//   "funnel":    {"outlet_width_m", "wall_angle_deg" (from the horizontal), "height_m", "outlet_height_m" (above
//                 the base), "fill_height_m" (default 0.8 x height), "solids_fraction" (default 0.4),
//                 "base_width_m", "domain_width_m" (the catch floor's width, default 3 x base)},
//   "run":       {"max_time_s", "fill_time_s", "check_every_s", "settle_kinetic_ratio", "jam_time_s",
//                 "discharged_fraction", "local_damping", "max_wall_s", "bin_width_diameters",
//                 "safety_factor" (the time step's share of the critical one, default 0.8)}
//
// Contact roles: "particle-particle" and "particle-wall" (base, funnel, gate, catch floor).
#include <map>
#include <string>

#include "demcal/dem/funnel_discharge.hpp"
#include "demcal/dem/powder_particles.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

struct HeapSpec {
  PowderSpec powder;
  double thickness_m = 0;
  // funnel
  double outlet_width_m = 0, wall_angle_deg = 60, funnel_height_m = 0, outlet_height_m = 0, fill_height_m = 0;
  double base_width_m = 0, domain_width_m = 0;
  // run: the stages' keys (funnel_discharge.hpp) and the step's and the fit's
  FunnelRun run;
  double local_damping = 0, bin_width_diameters = 1.5, safety_factor = 0.8;

  double top_width_m() const;  // the funnel's width at its top
  // Reads the scene's sections with `parameters`; throws an Error naming the scene file and the field.
  static HeapSpec from_scene(const Scene& scene, const std::map<std::string, double>& parameters);
};

TestResult run_heap(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

}  // namespace demcal::dem
