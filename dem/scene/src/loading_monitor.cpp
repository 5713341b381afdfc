#include "demcal/dem/loading_monitor.hpp"

#include <algorithm>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/core/wall_timeout.hpp"

namespace demcal::dem {
namespace {

// Least-squares slope of y(point) on the axial strain over curve[from..to].
template <typename Y>
double slope_on_axial_strain(const std::vector<CurvePoint>& curve, std::size_t from, std::size_t to, Y y) {
  double se = 0, sy = 0, see = 0, sey = 0;
  const double n = static_cast<double>(to - from + 1);
  for (std::size_t k = from; k <= to; ++k) {
    const double e = curve[k].axial_strain, v = y(curve[k]);
    se += e;
    sy += v;
    see += e * e;
    sey += e * v;
  }
  return (n * sey - se * sy) / (n * see - se * se);
}

}  // namespace

LoadingMonitor::LoadingMonitor(const LoadingSpec& loading, const RunOptions& options,
                               std::chrono::steady_clock::time_point start, double work_m3)
    : loading_(loading), options_(options), start_(start), work_m3_(work_m3) {
  if (options.progress) progress_ = std::make_unique<Progress>("loading (% of the strain limit)", 100);
}

LoadingMonitor::~LoadingMonitor() = default;

bool LoadingMonitor::record(const MonitoredWorld& world, const CurvePoint& point, TestResult& result, const std::string& where) {
  const CurvePoint before = result.curve.empty() ? CurvePoint{} : result.curve.back();
  work_j_ += 0.5 * (point.stress_pa + before.stress_pa) * (point.axial_strain - before.axial_strain) * work_m3_;
  result.curve.push_back(point);
  world.snapshot(options_, result.curve.size(), false);
  if (point.stress_pa > peak_) {
    peak_ = point.stress_pa;
    peak_index_ = result.curve.size() - 1;
  }
  const std::string unstable = world.instability(loading_.platen_velocity_m_s);
  if (!unstable.empty()) {
    // Bonds breaking throw disks off faster than 1000 x the platen speed: a
    // brittle specimen's burst at failure (tens of m/s, as in the laboratory,
    // and sqrt(k) times faster when every stiffness and strength is k times
    // larger), but at slow platens also one bond's break before the peak (a
    // contact bond's spring energy F^2 / 2k can throw an edge disk at
    // F / sqrt(k m), about 15 m/s on the sandstone: docs/explanation/fidelity.md). Neither
    // ends the test: it goes on to its own end (the stress falling past the
    // peak, the strain limit), so the peak is the specimen's. Energy the
    // platens never put in is a numerical instability, and fast disks with no
    // bond breaking, like everything else here, stay a failure.
    bool burst = false;
    if (unstable.find("faster than") != std::string::npos) {
      const double kinetic_j = world.kinetic_energy_j();
      if (kinetic_j > work_j_) {
        result.reason = "unstable: the kinetic energy (" + format_double(kinetic_j) +
                        " J) exceeds the work the platens did (" + format_double(work_j_) + " J) at " + where;
        return false;
      }
      // Bonds breaking now: within the last three recorded points.
      const std::size_t n = result.curve.size();
      burst = n >= 10 && point.cracks > result.curve[n - 4].cracks;
    }
    if (!burst) {
      result.reason = unstable + " at " + where;
      return false;
    }
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed > loading_.max_wall_s) {
    result.reason = wall_timeout_reason("after " + std::to_string(elapsed) + " s (loading.max_wall_s)");
    return false;
  }
  if (progress_) {
    const int percent = std::min(100, static_cast<int>(100 * point.axial_strain / loading_.strain_limit));
    if (percent > shown_) {
      progress_->advance(static_cast<std::uint64_t>(percent - shown_));
      shown_ = percent;
    }
  }
  const bool past_peak = world.breaks() > 0 && result.curve.size() >= 10 &&
                         result.curve.size() > peak_index_ + 2 &&
                         point.stress_pa < loading_.stop_fraction_of_peak * peak_;
  if (past_peak || point.axial_strain >= loading_.strain_limit) {
    result.ok = true;
    result.ended_by = past_peak ? "stress below stop_fraction_of_peak" : "strain_limit";
    return false;
  }
  return true;
}

std::map<std::string, double> ucs_macro_values(const std::vector<CurvePoint>& curve,
                                               const std::vector<double>* tangent_lateral_strain) {
  if (curve.size() < 5) throw Error("too few curve points to evaluate the test");
  if (tangent_lateral_strain && tangent_lateral_strain->size() != curve.size())
    throw Error("the tangent lateral strain has " + std::to_string(tangent_lateral_strain->size()) +
                " values for " + std::to_string(curve.size()) + " curve points");
  std::size_t peak = 0;
  for (std::size_t k = 1; k < curve.size(); ++k)
    if (curve[k].stress_pa > curve[peak].stress_pa) peak = k;
  const double sigma_u = curve[peak].stress_pa;
  std::size_t half = 0;
  while (half < peak && curve[half].stress_pa < 0.5 * sigma_u) ++half;
  // Tangents at the half-peak point, E and nu over the same window: a
  // least-squares slope over its neighbours, a tenth of the points to the
  // peak on each side. A twentieth scattered nu over seeds by 12 % on a weak
  // sandstone where a tenth gives 9 % (20 seeds, docs/explanation/calibration_method.md), and a
  // line through points set evenly about one point of a parabola still has
  // its slope there.
  const std::size_t window = std::max<std::size_t>(2, peak / 10);
  const std::size_t from = half > window ? half - window : 0, to = std::min(peak, half + window);
  std::map<std::string, double> macro;
  macro["sigma_u_MPa"] = sigma_u / 1e6;
  macro["E_GPa"] = slope_on_axial_strain(curve, from, to, [](const CurvePoint& p) { return p.stress_pa; }) / 1e9;
  macro["E50_GPa"] = curve[half].stress_pa / curve[half].axial_strain / 1e9;
  if (tangent_lateral_strain) {
    const CurvePoint* first = curve.data();
    macro["nu"] = slope_on_axial_strain(curve, from, to, [&](const CurvePoint& p) {
      return (*tangent_lateral_strain)[static_cast<std::size_t>(&p - first)];
    });
  } else {
    macro["nu"] = slope_on_axial_strain(curve, from, to, [](const CurvePoint& p) { return p.lateral_strain; });
  }
  // The secant at the same point, as Su et al. 2021 define their nu (E50's partner).
  macro["nu50"] = curve[half].lateral_strain / curve[half].axial_strain;
  macro["peak_strain"] = curve[peak].axial_strain;
  return macro;
}

}  // namespace demcal::dem
