// Brazilian disc test: a disc cut from a square packing, flattened where the
// platens bear, loaded across its diameter; tensile strength
// sigma_t = 2 F_max / (pi D t).
#include <algorithm>
#include <chrono>
#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/dem/builtin_tests.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/platen_test.hpp"
#include "demcal/dem/brazilian_test.hpp"

namespace demcal::dem {

TestResult run_brazilian(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const LoadingSpec& loading = scene.loading();
  Specimen square = cached_specimen(specimen_spec(scene, parameters, options.seed), options.cache_dir);
  const double D = std::min(square.width_m, square.height_m);
  const double cx = 0.5 * square.width_m, cy = 0.5 * square.height_m;
  // The disc is flattened where the platens load it (a 2 x 10 degree chord
  // at each end), so each platen bears on several disks from the start
  // instead of crushing a single one; sigma_t keeps the plain formula. The
  // platens start on the flats, touching every disk that crosses a flat with
  // its centre inside the disc, with no force (as a prism's start at its
  // vessel's faces): otherwise the first approach closes the flats'
  // roughness on one or two disks, whose local breaks could end the test
  // long before the disc splits (loading.platen_start "outermost_disks"
  // keeps that start, and only the disks wholly inside the flattened disc).
  const double flat = 0.5 * D * std::cos(10.0 * M_PI / 180.0);
  const bool on_flats = loading.platen_start == LoadingSpec::PlatenStart::vessel_faces;
  std::vector<bool> keep(square.size());
  std::size_t kept = 0;
  for (std::size_t i = 0; i < square.size(); ++i) {
    const double dy = std::abs(square.y[i] - cy), centre = std::hypot(square.x[i] - cx, square.y[i] - cy);
    const double r = square.radius[i];
    // Inside the disc, or (on the flats) crossing a flat with its centre
    // inside the circle: the flats are shallower than a disk (0.015 D), so a
    // disk that touches one reaches past the circle.
    keep[i] = on_flats ? dy <= flat && (centre + r <= 0.5 * D || (dy + r > flat && centre <= 0.5 * D))
                       : centre + r <= 0.5 * D && dy + r <= flat;
    kept += keep[i];
    // A disk crossing a flat by more than half its radius is set back to half
    // (the flats ground true): deeper, little force would push it through the
    // platen. Bonding makes its new overlaps force-free as they lie.
    if (on_flats && keep[i] && dy > flat - 0.5 * r)
      square.y[i] = cy + std::copysign(flat - 0.5 * r, square.y[i] - cy);
  }
  std::map<std::string, double> specimen_info;
  const std::pair<double, double> flats{cy - flat, cy + flat};
  World world = make_platen_world(scene, parameters, square, options.seed, &keep, &specimen_info, false,
                                  on_flats ? &flats : nullptr, &options);
  const double t = square.thickness_m;
  const double gap0 = world.wall(kTopWall).y0 - world.wall(kBottomWall).y0;

  TestResult result;
  result.specimen_info = specimen_info;
  result.particles = kept;
  result.porosity = square.porosity;
  const auto loading_start = std::chrono::steady_clock::now();
  double next_record = 0;
  // sigma = 2 F / (pi D t) and the approach over D: F d(approach) = sigma d(approach / D) pi D^2 t / 2.
  LoadingMonitor monitor(loading, options, start, 0.5 * M_PI * D * D * t);
  for (;;) {
    world.step();
    const double approach = (gap0 - (world.wall(kTopWall).y0 - world.wall(kBottomWall).y0)) / D;
    if (approach < next_record) continue;
    next_record = approach + loading.record_strain;
    CurvePoint point;
    point.axial_strain = approach;
    point.stress_pa = 2.0 * platen_force(world) / (M_PI * D * t);
    point.cracks = world.breaks().size();
    if (!monitor.record(DiskMonitoredWorld(world), point, result, "platen approach " + std::to_string(approach) + " D")) break;
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    std::size_t peak_index = 0;
    for (std::size_t k = 1; k < result.curve.size(); ++k)
      if (result.curve[k].stress_pa > result.curve[peak_index].stress_pa) peak_index = k;
    result.macro["sigma_t_MPa"] = monitor.peak() / 1e6;
    result.macro["peak_approach_over_D"] = result.curve[peak_index].axial_strain;
  }
  return result;
}

namespace {

class BrazilianTest : public PackedTest {
 public:
  std::string name() const override { return "brazilian"; }
  std::string description() const override {
    return "Brazilian disc: a disc cut from the packing, flattened where the platens bear, split across its diameter";
  }
  std::vector<BoundaryRole> boundary_roles() const override { return {platen_role()}; }
  // 1: the platens start on the flats, force-free (2026-12-03).
  int results_version() const override { return 1; }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"sigma_t_MPa"}; }
  std::pair<std::string, std::string> curve_axes() const override {
    return {"platen approach / D", "2F / (pi D t) (MPa)"};
  }
  std::vector<OutputSpec> outputs(const Scene& scene) const override {
    std::vector<OutputSpec> out = {
        {"sigma_t_MPa", "MPa", "tensile strength 2 F_max / (pi D t)", true, kNonNegative},
        {"peak_approach_over_D", "1", "platen approach at the peak force over the diameter", true, kNonNegative},
    };
    for (OutputSpec& o : platen_crack_outputs(scene)) out.push_back(o);
    return out;
  }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_brazilian(scene, parameters, options);
  }
};

}  // namespace

void register_brazilian_test(LabTestRegistry& registry) { registry.add(std::make_unique<BrazilianTest>()); }

}  // namespace demcal::dem
