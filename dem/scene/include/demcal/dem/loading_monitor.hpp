#pragma once
// A loading run's curve and its end, for the platen tests of either engine:
// past the peak (bonds have broken and the stress has fallen below the stop
// fraction of the peak a few points later, so an elastic dip does not count),
// at the strain limit, on instability or on timeout. Draws the progress line.
//
// A particle faster than 1000 x the platen speed is either bonds breaking (a
// brittle burst at failure, or at slow platens one bond's break before the
// peak) or a numerical instability (energy out of nothing). The energy budget
// tells them apart: the kinetic energy can never exceed the work the platens
// have done, so with bonds breaking (within the last three recorded points)
// and less energy than that the test goes on to its own end; otherwise the run
// fails. `work_m3` turns the curve into that work: the platen force times its
// approach is stress x strain x work_m3. (A locked-in stress adds energy the
// platens did not put in; a large one may make a burst look like an
// instability.)
#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal {
class Progress;
}

namespace demcal::dem {

// What the monitor asks of a run's world, whichever engine runs it.
class MonitoredWorld {
 public:
  virtual ~MonitoredWorld() = default;
  // Empty when the state is sane, else why the run must stop ("... faster
  // than 1000 x the platen speed" for a particle that is only fast).
  virtual std::string instability(double platen_velocity_m_s) const = 0;
  virtual double kinetic_energy_j() const = 0;
  virtual std::size_t breaks() const = 0;
  // Writes VTK snapshots when due (options.vtk_dir, vtk_every; `final` at the end).
  virtual void snapshot(const RunOptions& options, std::size_t points, bool final) const = 0;
};

class LoadingMonitor {
 public:
  LoadingMonitor(const LoadingSpec& loading, const RunOptions& options, std::chrono::steady_clock::time_point start,
                 double work_m3);
  ~LoadingMonitor();
  // Adds `point`; false when the run ends (result.ok set when it ended as
  // planned, result.reason when it failed; `where` says where, for the reason).
  bool record(const MonitoredWorld& world, const CurvePoint& point, TestResult& result, const std::string& where);
  double peak() const { return peak_; }

 private:
  const LoadingSpec& loading_;
  const RunOptions& options_;
  std::chrono::steady_clock::time_point start_;
  std::unique_ptr<Progress> progress_;
  int shown_ = 0;
  double peak_ = 0;
  std::size_t peak_index_ = 0;
  double work_m3_ = 0;
  double work_j_ = 0;  // done by the platens so far
};

// sigma_u, E (tangent where the stress first reaches half the peak, a
// least-squares slope over its neighbours), E50 (secant there), nu (tangent
// d eps_lat / d eps_ax over E's window), nu50 (secant eps_lat / eps_ax at the
// half-peak point) and the peak strain. nu50 uses the curve's lateral strain;
// nu uses `tangent_lateral_strain` (one value per curve point) when given,
// else the curve's too.
std::map<std::string, double> ucs_macro_values(const std::vector<CurvePoint>& curve,
                                               const std::vector<double>* tangent_lateral_strain = nullptr);

}  // namespace demcal::dem
