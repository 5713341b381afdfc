// Brazilian disc test: a disc cut from a square packing, flattened where the
// platens bear, loaded across its diameter; tensile strength
// sigma_t = 2 F_max / (pi D t).
#include <algorithm>
#include <chrono>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/ucs_test.hpp"

namespace demcal::dem {

TestResult run_brazilian(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const LoadingSpec& loading = scene.loading();
  Specimen square = cached_specimen(scene.specimen(parameters, options.seed), options.cache_dir);
  const double D = std::min(square.width_m, square.height_m);
  const double cx = 0.5 * square.width_m, cy = 0.5 * square.height_m;
  // The disc is flattened where the platens load it (a 2 x 10 degree chord
  // at each end), so each platen bears on several disks from the start
  // instead of crushing a single one; sigma_t keeps the plain formula.
  const double flat = 0.5 * D * std::cos(10.0 * M_PI / 180.0);
  std::vector<bool> keep(square.size());
  std::size_t kept = 0;
  for (std::size_t i = 0; i < square.size(); ++i) {
    keep[i] = std::hypot(square.x[i] - cx, square.y[i] - cy) + square.radius[i] <= 0.5 * D &&
              std::abs(square.y[i] - cy) + square.radius[i] <= flat;
    kept += keep[i];
  }
  World world = make_platen_world(scene, parameters, square, options.seed, &keep);
  const double t = square.thickness_m;
  const double gap0 = world.walls[1].y0 - world.walls[0].y0;

  TestResult result;
  result.particles = kept;
  result.porosity = square.porosity;
  const auto loading_start = std::chrono::steady_clock::now();
  double peak = 0, next_record = 0;
  std::size_t peak_index = 0;
  for (;;) {
    world.step();
    const double approach = (gap0 - (world.walls[1].y0 - world.walls[0].y0)) / D;
    if (approach < next_record) continue;
    next_record = approach + loading.record_strain;
    CurvePoint point;
    point.axial_strain = approach;
    point.stress_pa = 2.0 * platen_force(world) / (M_PI * D * t);
    point.cracks = world.breaks().size();
    result.curve.push_back(point);
    snapshot(world, options, result.curve.size(), false);
    if (point.stress_pa > peak) {
      peak = point.stress_pa;
      peak_index = result.curve.size() - 1;
    }
    result.reason = instability(world, loading.platen_velocity_m_s);
    if (!result.reason.empty()) {
      result.reason += " at platen approach " + std::to_string(approach) + " D";
      break;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > loading.max_wall_s) {
      result.reason = "timeout after " + std::to_string(elapsed) + " s (loading.max_wall_s)";
      break;
    }
    const bool past_peak = !world.breaks().empty() && result.curve.size() >= 10 &&
                           result.curve.size() > peak_index + 2 && point.stress_pa < loading.stop_fraction_of_peak * peak;
    if (past_peak || approach >= loading.strain_limit) {
      result.ok = true;
      break;
    }
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    result.macro["sigma_t_MPa"] = peak / 1e6;
    result.macro["peak_approach_over_D"] = result.curve[peak_index].axial_strain;
  }
  return result;
}

TestResult run_test(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  if (scene.test() == "ucs") return run_ucs(scene, parameters, options);
  if (scene.test() == "brazilian") return run_brazilian(scene, parameters, options);
  throw Error(scene.origin() + ": no runner for test \"" + scene.test() + "\"");
}

}  // namespace demcal::dem
