#pragma once
// Slope test (Ma et al. 2022's rockfill slope): a section of bedrock with
// zones of rockfill on it (slope_specimen.hpp), brought to rest under
// gravity against walls on the left, right and bottom; the walls are then
// replaced by the wave strip's boundaries (wave_boundary.hpp: each keeps the
// static force its wall gave; viscous and input sides add dashpots), and a
// wave enters through the input side: the cosine pulse of a boundary
// calibration, or an earthquake record (ground_motion.hpp). Monitoring
// points placed in metres record the particle
// velocity; the outputs are each point's recovery time and peak, the sum of
// the recovery times over the points the scene names as its objective (Ma et
// al.'s fitness), and the rockfill deposit's extent. A test of its own
// beside the wave strip, sharing its boundary, medium, pulse and monitor keys
// and its output names: the strip's sections assume a rectangle and fractions
// of it, a slope has a free surface and points in metres.
// docs/reference/lab_tests/slope.md.
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/ground_motion.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/slope_specimen.hpp"
#include "demcal/dem/test_result.hpp"
#include "demcal/dem/wave_boundary.hpp"

namespace demcal::dem {

struct SlopeMonitorSpec {
  std::string label;  // "3-3": column-row, as Ma et al. number theirs
  double x_m = 0, y_m = 0;
};

// An earthquake record sent in through the input edge instead of the pulse.
struct EarthquakeSpec {
  std::string record_path;           // resolved against the scene file's folder
  RecordFormat format = RecordFormat::values;
  double time_step_s = 0;            // the record's (values format: required)
  double to_m_s2 = 9.80665;          // the record's unit in m/s^2 ("g" or "m/s2")
  double scale = 1;
  double duration_s = 0;             // the first seconds used; 0: all of it
  bool s_wave = true;                // S (along the edge) or P (along its inward normal)
  Baseline baseline = Baseline::end_at_rest;
  GroundMotion motion;  // the record read, scaled, integrated and corrected when the scene is read
};

struct SlopeTestSpec {
  // Sides in the order of the walls: bottom, left, right (the top is the free surface).
  static constexpr std::array<const char*, 3> kSideNames = {"bottom", "left", "right"};
  SlopeSpec geometry;
  double bond_gap_tolerance_m = 0;  // 0: 1 % of the smallest radius
  std::array<SideSpec, 3> sides;
  std::size_t input_side = 0;
  MediumSpec medium;                          // the bedrock's continuum
  std::map<std::string, MediumSpec> zone_medium;  // a zone's own, by name (needed where its disks meet a dashpot side)
  PulseSpec pulse;
  bool earthquake_input = false;  // the input edge carries `earthquake`, not `pulse`
  EarthquakeSpec earthquake;
  std::vector<SlopeMonitorSpec> monitors;
  std::vector<std::string> objective;  // labels summed into total_recovery_time_s (all points when empty)
  double monitor_radius_m = 0;         // 0: twice the largest radius of the disks
  // The run.
  double duration_s = 6, gravity_m_s2 = 9.81, record_every_s = 0.01, recovery_fraction = 0.05;
  double recovery_speed_m_s = 0;  // > 0: a point is quiet below this speed (else recovery_fraction of the carried peak)
  double quiet_time_s = 0.5, equilibrium_ratio = 1e-3, max_equilibrium_steps = 200000;
  double equilibrium_damping = 0.7, local_damping = 0, max_wall_s = 1800;
  double max_speed_m_s = 100;  // a disk faster than this fails the run as unstable
  // > 0: the run ends once the input is over and every material's mean unbalanced-force ratio is below it.
  double stop_force_ratio = 0;
  // > 0: every this much simulated time the wave run is checkpointed in the cache, so a run that stops (a crash,
  // run.max_wall_s) resumes from there when run again, with the same bits.
  double checkpoint_every_s = 0;

  // Reads the scene's sections with `parameters`; throws an Error naming the scene file and the field.
  static SlopeTestSpec from_scene(const Scene& scene, const std::map<std::string, double>& parameters);
};

TestResult run_slope(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// Output names use the label with '-' as '_' ("recovery_time_s_3_3").
std::string slope_output_label(const std::string& label);

}  // namespace demcal::dem
