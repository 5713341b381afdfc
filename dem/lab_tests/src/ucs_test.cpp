#include "demcal/dem/ucs_test.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "demcal/core/error.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/dem/builtin_tests.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem/platen_test.hpp"

namespace demcal::dem {
namespace {

// Median x-displacement of a gauge set since the start: one disk group that
// spalls off the face (an early edge crack) moves the median little, the mean
// a lot.
double median_shift_x(const Bodies& b, const std::vector<std::size_t>& ids, const std::vector<double>& x0,
                      std::vector<double>& scratch) {
  scratch.resize(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) scratch[k] = b.x[ids[k]] - x0[k];
  const std::size_t mid = scratch.size() / 2;
  std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(mid), scratch.end());
  if (scratch.size() % 2) return scratch[mid];
  const double upper = scratch[mid];
  return 0.5 * (upper + *std::max_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(mid)));
}

double mean_x(const Bodies& b, const std::vector<std::size_t>& ids) {
  double sum = 0;
  for (std::size_t i : ids) sum += b.x[i];
  return sum / static_cast<double>(ids.size());
}

// Both platens approach at `speed_m_s` (bottom up, top down).
void set_platen_speed(World& world, double speed_m_s) {
  world.wall(kBottomWall).vy = speed_m_s;
  world.wall(kTopWall).vy = -speed_m_s;
}

}  // namespace

LateralStrainFit::LateralStrainFit(const std::vector<double>& x, std::vector<std::size_t> ids) : ids_(std::move(ids)) {
  double mean = 0;
  for (std::size_t i : ids_) mean += x[i];
  mean /= static_cast<double>(ids_.size());
  for (std::size_t i : ids_) {
    x0_.push_back(x[i]);
    centred_x0_.push_back(x[i] - mean);
    sxx_ += (x[i] - mean) * (x[i] - mean);
  }
  if (!(sxx_ > 0)) throw Error("a lateral strain fit needs disks at two or more x positions");
}

std::vector<std::size_t> disks_in_band(const Bodies& b, double y0_m, double bottom_m, double top_m) {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double height = b.y[i] - y0_m;
    if (height >= bottom_m && height <= top_m) indices.push_back(i);
  }
  std::sort(indices.begin(), indices.end(), [&](std::size_t i, std::size_t j) { return b.id[i] < b.id[j]; });
  return indices;
}

double LateralStrainFit::strain(const std::vector<double>& x) const {
  double sxd = 0;
  for (std::size_t k = 0; k < ids_.size(); ++k) sxd += centred_x0_[k] * (x[ids_[k]] - x0_[k]);
  return sxd / sxx_;
}

TestResult run_ucs(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const LoadingSpec& loading = scene.loading();
  SpecimenSpec spec = specimen_spec(scene, parameters, options.seed);
  Specimen specimen = cached_specimen(spec, options.cache_dir);

  std::map<std::string, double> specimen_info;
  World world = make_platen_world(scene, parameters, specimen, options.seed, nullptr, &specimen_info, false, nullptr,
                                  &options);
  const double W = specimen.width_m, H0 = world.wall(kTopWall).y0 - world.wall(kBottomWall).y0;

  // Lateral strain from the outermost disks of the middle third of the height.
  // The gauges hold the world's indices of those disks in the order of their
  // ids, so their sums do not depend on the order the disks are stored in.
  const Bodies& b = world.bodies;
  const double r_max = *std::max_element(b.radius.begin(), b.radius.end());
  std::vector<std::size_t> left, right;
  for (std::size_t i : disks_in_band(b, world.wall(kBottomWall).y0, H0 / 3, 2 * H0 / 3)) {
    if (b.x[i] - b.radius[i] < 2 * r_max) left.push_back(i);
    if (b.x[i] + b.radius[i] > W - 2 * r_max) right.push_back(i);
  }
  if (left.empty() || right.empty()) throw Error("specimen too small to measure lateral strain");
  const double width0 = mean_x(world.bodies, right) - mean_x(world.bodies, left);
  std::vector<double> left_x0, right_x0, scratch;
  for (std::size_t i : left) left_x0.push_back(world.bodies.x[i]);
  for (std::size_t i : right) right_x0.push_back(world.bodies.x[i]);
  // nu's tangent comes from every disk of the middle three fifths
  // (LateralStrainFit): over E's short window the two edge gauges scattered
  // 1.5-2x more from seed to seed, and the middle third alone 1.4-1.5x more.
  const double bottom_y = world.wall(kBottomWall).y0;
  const LateralStrainFit bulk_gauge(world.bodies.x,
                                    disks_in_band(b, bottom_y, kNuGaugeBottomFraction * H0, kNuGaugeTopFraction * H0));
  std::vector<double> bulk_lateral_strain;

  TestResult result;
  result.specimen_info = specimen_info;
  const auto loading_start = std::chrono::steady_clock::now();
  result.particles = specimen.size();
  result.porosity = specimen.porosity;
  double next_record = 0;
  // Faster platens while every bond is far from its strength
  // (loading.elastic_speedup), slowed at each curve point.
  bool fast = loading.elastic_speedup > 1;
  if (fast) {
    if (std::isnan(world.max_bond_utilisation()))
      throw Error(scene.origin() + ": loading.elastic_speedup: none of the specimen's contact models reports how close "
                  "its bonds are to breaking (parallel_bond and contact_bond do)");
    set_platen_speed(world, loading.elastic_speedup * loading.platen_velocity_m_s);
  }
  LoadingMonitor monitor(loading, options, start, W * H0 * specimen.thickness_m);
  for (;;) {
    world.step();
    const double height = world.wall(kTopWall).y0 - world.wall(kBottomWall).y0;
    const double strain = (H0 - height) / H0;
    if (strain < next_record) continue;
    next_record = strain + loading.record_strain;
    CurvePoint point;
    point.axial_strain = strain;
    point.stress_pa = platen_force(world) / (W * specimen.thickness_m);
    point.lateral_strain = (median_shift_x(world.bodies, right, right_x0, scratch) -
                            median_shift_x(world.bodies, left, left_x0, scratch)) / width0;
    point.cracks = world.breaks().size();
    bulk_lateral_strain.push_back(bulk_gauge.strain(world.bodies.x));
    if (!monitor.record(DiskMonitoredWorld(world), point, result, "axial strain " + std::to_string(strain))) break;
    if (fast) {
      // The speed falls in proportion as the most loaded bond takes up its
      // strength, never rising again: a gradual slowing rings the specimen
      // far less than one step down would.
      const double share = world.breaks().empty()
                               ? std::max(0.0, 1.0 - world.max_bond_utilisation() / loading.speedup_until_utilisation)
                               : 0.0;
      const double speed = std::min(-world.wall(kTopWall).vy,  // the top platen's present speed
                                    loading.platen_velocity_m_s * (1 + (loading.elastic_speedup - 1) * share));
      set_platen_speed(world, speed);
      if (share == 0) {
        fast = false;
        result.specimen_info["elastic_speedup_until_strain"] = strain;
      }
    }
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    try {
      for (const auto& [name, value] : ucs_macro_values(result.curve, &bulk_lateral_strain)) result.macro[name] = value;
    } catch (const Error& e) {
      result.ok = false;
      result.reason = e.what();
    }
    if (result.ok && result.ended_by == "strain_limit") result.macro["reached_strain_limit"] = 1;
  }
  return result;
}

namespace {

class UcsTest : public PackedTest {
 public:
  std::string name() const override { return "ucs"; }
  std::string description() const override {
    return "uniaxial compression between two frictionless platens approaching at the loading velocity";
  }
  std::vector<BoundaryRole> boundary_roles() const override { return {platen_role()}; }
  // 1: nu's tangent from the bulk lateral strain fit (LateralStrainFit).
  // 2: E's and nu's window a tenth of the points to the peak (was a twentieth).
  // 3: nu's fit over the middle three fifths of the height (was the middle third).
  int results_version() const override { return 3; }
  std::vector<OutputSpec> outputs(const Scene& scene) const override {
    std::vector<OutputSpec> out = {
        {"sigma_u_MPa", "MPa", "peak axial stress (platen force / (W t))", true, kNonNegative},
        {"E_GPa", "GPa", "tangent Young's modulus where the stress first reaches half the peak (least squares over "
                         "a tenth of the points to the peak on each side)", true, kNonNegative},
        {"E50_GPa", "GPa", "secant modulus at half the peak", true, kNonNegative},
        {"nu", "1", "tangent Poisson's ratio d eps_lat / d eps_ax over the same window as E, the lateral strain "
                    "fitted to every disk of the middle three fifths of the height", true, kPoissonRatio2D},
        {"nu50", "1", "secant Poisson's ratio eps_lat / eps_ax where the stress first reaches half the peak (the "
                      "definition of Su et al. 2021), the lateral strain from the median edge disks of the middle third", true,
         kPoissonRatio2D},
        {"peak_strain", "1", "axial strain at the peak", true, kNonNegative},
        {"reached_strain_limit", "1", "1 when the test ended at loading.strain_limit before the post-peak stop",
         false, kFlag},
    };
    for (OutputSpec& o : platen_crack_outputs(scene)) out.push_back(o);
    return out;
  }
  bool speeds_up_while_elastic() const override { return true; }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"sigma_u_MPa", "E_GPa", "nu"}; }
  std::vector<std::string> modulus_outputs(const Scene&) const override { return {"E_GPa", "E50_GPa"}; }
  TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                 const RunOptions& options) const override {
    return run_ucs(scene, parameters, options);
  }
};

}  // namespace

void register_ucs_test(LabTestRegistry& registry) { registry.add(std::make_unique<UcsTest>()); }

}  // namespace demcal::dem
