#pragma once
// What every lab test returns: the run's curve, its macro values (the
// outputs its test declares), status and cost; and the options of a run.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace demcal::dem {

struct CurvePoint {
  double axial_strain = 0;    // platen approach / initial height (compression > 0)
  double stress_pa = 0;       // mean platen force / (W t) (compression > 0)
  double lateral_strain = 0;  // widening of the middle third / initial width (expansion > 0)
  std::size_t cracks = 0;     // bond breaks so far
  // Confined tests: the measured confining stress, and then stress_pa is the
  // deviatoric stress sigma_1 - sigma_3 (0 for unconfined tests).
  double confining_stress_pa = 0;
};

struct TestResult {
  bool ok = false;
  std::string reason;          // why it failed
  std::string ended_by;        // why a successful test stopped (post-peak fraction, strain limit)
  std::map<std::string, double> macro;  // sigma_u_MPa, E_GPa, E50_GPa, nu, peak_strain, cracks_*
  std::map<std::string, double> extra_outputs;  // an external command's numbers beyond its declared outputs
  std::vector<CurvePoint> curve;
  // A test whose record is not a stress-strain curve (a wave's velocity
  // histories) keeps named columns of equal length here; they are its curve.
  std::vector<std::pair<std::string, std::vector<double>>> series;
  std::size_t particles = 0;
  std::uint64_t steps = 0;
  double wall_s = 0;           // whole run, packing or cache load included
  double test_wall_s = 0;      // the loading alone (for particle-steps per second)
  int threads = 1;             // threads the run's force loop used at its end
  std::vector<double> thread_cuts;  // where its threads' parts of the pairs were at its end (thread_balance.hpp)
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
  std::string work_dir;   // the point's own folder: an external test's files (params, out, stdout, stderr)
  // What a run must not depend on, set by the invariant tests (tests/invariants):
  // the threads of its force loops (0: OpenMP's default), the disks per thread
  // below which it uses fewer (0: the engine's default), and a seed that
  // shuffles the order in which the particles enter the world, keeping their
  // ids (0: the order they were made in).
  int threads = 0;
  std::size_t min_disks_per_thread = 0;
  std::uint64_t particle_order_seed = 0;
};

}  // namespace demcal::dem
