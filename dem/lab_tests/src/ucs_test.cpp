#include "demcal/dem/ucs_test.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "demcal/core/error.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/platen_test.hpp"

namespace demcal::dem {
namespace {

double mean_x(const Bodies& b, const std::vector<std::size_t>& ids) {
  double sum = 0;
  for (std::size_t i : ids) sum += b.x[i];
  return sum / static_cast<double>(ids.size());
}

}  // namespace

std::map<std::string, double> ucs_macro_values(const std::vector<CurvePoint>& curve) {
  if (curve.size() < 5) throw Error("too few curve points to evaluate the test");
  std::size_t peak = 0;
  for (std::size_t k = 1; k < curve.size(); ++k)
    if (curve[k].stress_pa > curve[peak].stress_pa) peak = k;
  const double sigma_u = curve[peak].stress_pa;
  std::size_t half = 0;
  while (half < peak && curve[half].stress_pa < 0.5 * sigma_u) ++half;
  // Tangent at the half-peak point: least-squares slope over its neighbours.
  const std::size_t window = std::max<std::size_t>(2, peak / 20);
  const std::size_t from = half > window ? half - window : 0, to = std::min(peak, half + window);
  double se = 0, ss = 0, see = 0, ses = 0;
  const double n = static_cast<double>(to - from + 1);
  for (std::size_t k = from; k <= to; ++k) {
    se += curve[k].axial_strain;
    ss += curve[k].stress_pa;
    see += curve[k].axial_strain * curve[k].axial_strain;
    ses += curve[k].axial_strain * curve[k].stress_pa;
  }
  const double slope = (n * ses - se * ss) / (n * see - se * se);
  std::map<std::string, double> macro;
  macro["sigma_u_MPa"] = sigma_u / 1e6;
  macro["E_GPa"] = slope / 1e9;
  macro["E50_GPa"] = curve[half].stress_pa / curve[half].axial_strain / 1e9;
  macro["nu"] = curve[half].lateral_strain / curve[half].axial_strain;
  macro["peak_strain"] = curve[peak].axial_strain;
  return macro;
}

TestResult run_ucs(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const LoadingSpec& loading = scene.loading();
  SpecimenSpec spec = scene.specimen(parameters, options.seed);
  Specimen specimen = cached_specimen(spec, options.cache_dir);

  std::map<std::string, double> specimen_info;
  World world = make_platen_world(scene, parameters, specimen, options.seed, nullptr, &specimen_info);
  const double W = specimen.width_m, H0 = world.walls[1].y0 - world.walls[0].y0;

  // Lateral strain from the outermost disks of the middle third of the height.
  double r_max = *std::max_element(specimen.radius.begin(), specimen.radius.end());
  std::vector<std::size_t> left, right;
  for (std::size_t i = 0; i < specimen.size(); ++i) {
    const double y = specimen.y[i] - world.walls[0].y0;
    if (y < H0 / 3 || y > 2 * H0 / 3) continue;
    if (specimen.x[i] - specimen.radius[i] < 2 * r_max) left.push_back(i);
    if (specimen.x[i] + specimen.radius[i] > W - 2 * r_max) right.push_back(i);
  }
  if (left.empty() || right.empty()) throw Error("specimen too small to measure lateral strain");
  const double width0 = mean_x(world.bodies, right) - mean_x(world.bodies, left);

  TestResult result;
  result.specimen_info = specimen_info;
  const auto loading_start = std::chrono::steady_clock::now();
  result.particles = specimen.size();
  result.porosity = specimen.porosity;
  double next_record = 0;
  LoadingMonitor monitor(loading, options, start);
  for (;;) {
    world.step();
    const double height = world.walls[1].y0 - world.walls[0].y0;
    const double strain = (H0 - height) / H0;
    if (strain < next_record) continue;
    next_record = strain + loading.record_strain;
    CurvePoint point;
    point.axial_strain = strain;
    point.stress_pa = platen_force(world) / (W * specimen.thickness_m);
    point.lateral_strain = (mean_x(world.bodies, right) - mean_x(world.bodies, left) - width0) / width0;
    point.cracks = world.breaks().size();
    if (!monitor.record(world, point, result, "axial strain " + std::to_string(strain))) break;
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    try {
      for (const auto& [name, value] : ucs_macro_values(result.curve)) result.macro[name] = value;
    } catch (const Error& e) {
      result.ok = false;
      result.reason = e.what();
    }
    if (result.ok && result.ended_by == "strain_limit") result.macro["reached_strain_limit"] = 1;
  }
  return result;
}

namespace {

class UcsTest : public LabTest {
 public:
  std::string name() const override { return "ucs"; }
  std::string description() const override {
    return "uniaxial compression between two frictionless platens approaching at the loading velocity";
  }
  std::vector<BoundaryRole> boundary_roles() const override { return {platen_role()}; }
  std::vector<OutputSpec> outputs(const Scene& scene) const override {
    std::vector<OutputSpec> out = {
        {"sigma_u_MPa", "MPa", "peak axial stress (platen force / (W t))"},
        {"E_GPa", "GPa", "tangent Young's modulus where the stress first reaches half the peak"},
        {"E50_GPa", "GPa", "secant modulus at half the peak"},
        {"nu", "1", "Poisson's ratio: lateral over axial strain at half the peak"},
        {"peak_strain", "1", "axial strain at the peak"},
        {"reached_strain_limit", "1", "1 when the test ended at loading.strain_limit before the post-peak stop",
         false},
    };
    for (OutputSpec& o : platen_crack_outputs(scene)) out.push_back(o);
    return out;
  }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_ucs(scene, parameters, options);
  }
};

}  // namespace

void register_ucs_test(LabTestRegistry& registry) { registry.add(std::make_unique<UcsTest>()); }

}  // namespace demcal::dem
