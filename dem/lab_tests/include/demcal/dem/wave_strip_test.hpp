#pragma once
// Wave-strip test (Ma et al. 2022): a bonded strip, packed in its vessel and
// brought to rest under gravity against the vessel's walls, has the walls
// replaced by boundaries that keep their static force (boundary_forces.hpp);
// then a cosine pulse v = 0.5 A (1 - cos(2 pi t / T)), t <= T, enters through
// the input side and travels along the strip. Monitoring points record the
// particle velocity; the outputs are each point's recovery time (after which
// |v| stays below a share of the peak the pulse had at the point nearest the
// input), their sum, the reflection coefficient at a
// point near the far side, the P (and S) wave speeds measured from the
// arrivals, and the work the boundaries did. docs/explanation/wave_strip.md.
//
//   "boundaries": {"left"|"right"|"bottom"|"top": {"type": "fixed"|"free"|"viscous"|"input",
//                  "xi": number or expression, "eta": ...}}   (exactly one input side; free by default)
//   "medium":     {"E_d_Pa", "nu_d"} (the dashpots' C_P and C_S by the continuum formulas) and/or
//                 {"wave_speed_p_m_s", "wave_speed_s_m_s"} (given speeds, used instead);
//                 "p_speed_formula": "ma2022" (default: Ma et al.'s C_P, the plane-strain one their
//                 coefficients are relative to) or "plane_stress" (the 2D assembly's, sqrt(E / (rho (1 - nu^2))))
//   "pulse":      {"p_amplitude_m_s" (A, default 1), "s_amplitude_m_s" (default 0), "period_s" (T, default 0.2)}
//   "monitors":   {"points": [[x / W, y / H], ...] (T1, T2, ...), "reflection_point": [x / W, y / H],
//                  "radius_m" (default 2 x the largest radius)}
//   "run":        {"duration_s", "gravity_m_s2", "record_every_s", "recovery_fraction", "quiet_time_s",
//                  "equilibrium_ratio", "max_equilibrium_steps", "local_damping", "max_wall_s"}
//
// Contact roles: the specimen's own and "particle-wall" (the vessel's walls, until the boundaries replace them).
#include <array>
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"
#include "demcal/dem/wave_boundary.hpp"

namespace demcal::dem {

struct WaveStripSpec {
  // Sides in the wall order of make_platen_world: bottom, top, left, right.
  static constexpr std::array<const char*, 4> kSideNames = {"bottom", "top", "left", "right"};
  std::array<SideSpec, 4> sides;
  std::size_t input_side = 2;
  MediumSpec medium;  // the equivalent continuum behind the dashpots
  PulseSpec pulse;
  // Monitoring points, as fractions of the specimen's width and height.
  std::vector<std::array<double, 2>> points;
  std::array<double, 2> reflection_point = {0.75, 0.5};
  double monitor_radius_m = 0;  // 0: twice the largest radius
  // The run.
  double duration_s = 2.5, gravity_m_s2 = 9.81, record_every_s = 0.002, recovery_fraction = 0.05;
  double quiet_time_s = 0.2, equilibrium_ratio = 1e-4, max_equilibrium_steps = 200000, local_damping = 0;
  double max_wall_s = 600;

  // Reads the scene's sections with `parameters`; throws an Error naming the scene file and the field.
  static WaveStripSpec from_scene(const Scene& scene, const std::map<std::string, double>& parameters);
};

TestResult run_wave_strip(const Scene& scene, const std::map<std::string, double>& parameters,
                          const RunOptions& options);

}  // namespace demcal::dem
