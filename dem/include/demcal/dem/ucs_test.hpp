#pragma once
// Uniaxial compression between two frictionless platens: the stress-strain
// curve and the macro values a calibration targets.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/scene.hpp"

namespace demcal::dem {

struct CurvePoint {
  double axial_strain = 0;    // platen approach / initial height (compression > 0)
  double stress_pa = 0;       // mean platen force / (W t) (compression > 0)
  double lateral_strain = 0;  // widening of the middle third / initial width (expansion > 0)
  std::size_t cracks = 0;     // bond breaks so far
};

struct TestResult {
  bool ok = false;
  std::string reason;          // why it failed
  std::string ended_by;        // why a successful test stopped (post-peak fraction, strain limit, burst)
  std::map<std::string, double> macro;  // sigma_u_MPa, E_GPa, E50_GPa, nu, peak_strain, cracks_*
  std::vector<CurvePoint> curve;
  std::size_t particles = 0;
  std::uint64_t steps = 0;
  double wall_s = 0;           // whole run, packing or cache load included
  double test_wall_s = 0;      // the loading alone (for particle-steps per second)
  double porosity = 0;
  double dt_s = 0;
  double density_scaling_dt_s = 0;  // > 0 when masses were scaled (quasi-static run)
  std::map<std::string, double> specimen_info;  // concrete: aggregates placed, disks in them, ...
};

struct RunOptions {
  std::uint64_t seed = 1;
  std::string cache_dir;  // packed specimens; empty: pack every time
  bool progress = false;  // a progress line on stderr
  std::string vtk_dir;    // VTK snapshots (disks + bonds, breaks) when set
  int vtk_every = 25;     // a snapshot every this many curve points, plus the first and last
};

// Packs (or loads) the specimen, bonds it, and loads it to failure. Bad input
// throws; a run that goes unstable or times out returns ok = false with the reason.
TestResult run_ucs(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// Brazilian disc: a disc of the specimen's width, cut from its packing, split
// between platens; macro sigma_t_MPa = 2 F_max / (pi D t).
TestResult run_brazilian(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// Runs the scene's lab test (LabTestRegistry) and checks that it reported
// only outputs it declares, and every output it always reports.
TestResult run_test(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// sigma_u, E (tangent where the stress first reaches half the peak), E50
// (secant there), nu (lateral over axial strain there) and the peak strain.
std::map<std::string, double> ucs_macro_values(const std::vector<CurvePoint>& curve);

}  // namespace demcal::dem
