// Uniaxial compression of a sphere cylinder (PFC3D's 1:2 specimen) between two
// frictionless platens, with the 2D test's outputs so studies and targets
// carry over: sigma_u, E and nu over the same window (tangents where the
// stress first reaches half the peak), E50, nu50, the peak strain and the
// cracks by mode. The lateral strain is the least-squares radial strain of
// the spheres on the lateral surface in the middle third of the height: their
// radial displacement u against their starting radius r0, u = eps r0.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "demcal/core/error.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/material_pressure.hpp"
#include "demcal/dem3d/sphere_scene.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::size_t kBottom = 0, kTop = 1;

// The spheres of the lateral surface of the middle third, in id order (so the
// fit's sums do not depend on how the spheres are stored), and their radial
// distances at the start.
class RadialStrainGauge {
 public:
  RadialStrainGauge(const Spheres& s, double radius_m, double bottom_z, double height_m) {
    double r_max = 0;
    for (double r : s.radius) r_max = std::max(r_max, r);
    std::vector<std::pair<std::uint32_t, std::size_t>> by_id;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double z = s.z[i] - bottom_z, r = std::hypot(s.x[i], s.y[i]);
      if (z >= height_m / 3 && z <= 2 * height_m / 3 && r + s.radius[i] > radius_m - 2 * r_max)
        by_id.emplace_back(s.id[i], i);
    }
    std::sort(by_id.begin(), by_id.end());
    for (const auto& [id, i] : by_id) {
      ids_.push_back(id);
      r0_.push_back(std::hypot(s.x[i], s.y[i]));
      srr_ += r0_.back() * r0_.back();
    }
    if (ids_.size() < 8) throw Error("specimen too small to measure the lateral strain (fewer than 8 surface spheres)");
    id_end_ = ids_.back() + 1;  // ids_ ascending
  }
  // Expansion positive. The spheres are found by id (the world reorders its
  // arrays), through one table per call: a search per sphere would cost
  // the gauge times the specimen.
  double strain(const World& w) const {
    const Spheres& s = w.spheres;
    index_by_id_.assign(id_end_, UINT32_MAX);
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.id[i] < id_end_) index_by_id_[s.id[i]] = static_cast<std::uint32_t>(i);
    double sru = 0;
    for (std::size_t k = 0; k < ids_.size(); ++k) {
      const std::uint32_t i = index_by_id_[ids_[k]];
      if (i == UINT32_MAX) throw Error("a lateral gauge sphere (id " + std::to_string(ids_[k]) + ") left the world");
      sru += r0_[k] * (std::hypot(s.x[i], s.y[i]) - r0_[k]);
    }
    return sru / srr_;
  }
  std::size_t size() const { return ids_.size(); }

 private:
  std::vector<std::uint32_t> ids_;
  std::vector<double> r0_;
  double srr_ = 0;
  std::uint32_t id_end_ = 0;
  mutable std::vector<std::uint32_t> index_by_id_;
};

void set_platen_speed(World& w, double speed_m_s) {
  w.walls[kBottom].velocity_m_s = {0, 0, speed_m_s};
  w.walls[kTop].velocity_m_s = {0, 0, -speed_m_s};
}

dem::TestResult run_ucs_3d(const Scene& scene, const std::map<std::string, double>& parameters,
                           const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const dem::LoadingSpec& loading = scene.loading();
  dem::TestResult result;
  SphereSpecimen specimen;
  if (!test_specimen(scene, parameters, options, result, specimen)) return result;

  World world = specimen_world(scene, parameters, specimen, options);
  // The vessel's end faces become the platens, touching the spheres that touched them with no force.
  world.walls = {make_plane({0, 0, 0}, {0, 0, 1}, kPlatenGroup),
                 make_plane({0, 0, specimen.height_m}, {0, 0, -1}, kPlatenGroup)};
  result.reason = bond_specimen(world, scene, specimen, options.seed, result.specimen_info);
  if (!result.reason.empty()) return result;

  // The platens' places from the walls: a pressured specimen's were set back on it after it relaxed.
  const double bottom_z = world.walls[kBottom].point_m.z;
  const double D = specimen.width_m, H0 = world.walls[kTop].point_m.z - bottom_z, area = 0.25 * M_PI * D * D;
  const RadialStrainGauge gauge(world.spheres, 0.5 * D, bottom_z, H0);
  result.particles = specimen.size();
  result.porosity = specimen.porosity;
  result.specimen_info["lateral_gauge_spheres"] = static_cast<double>(gauge.size());

  set_platen_speed(world, loading.platen_velocity_m_s);
  const auto loading_start = std::chrono::steady_clock::now();
  dem::LoadingMonitor monitor(loading, options, start, area * H0);
  double next_record = 0;
  for (;;) {
    world.step();
    const double height = world.walls[kTop].point_m.z - world.walls[kBottom].point_m.z;
    const double strain = (H0 - height) / H0;
    if (strain < next_record) continue;
    next_record = strain + loading.record_strain;
    dem::CurvePoint point;
    point.axial_strain = strain;
    point.stress_pa = 0.5 * (world.walls[kBottom].normal_force_n + world.walls[kTop].normal_force_n) / area;
    point.lateral_strain = gauge.strain(world);
    point.cracks = world.breaks().size();
    if (!monitor.record(SphereMonitoredWorld(world), point, result, "axial strain " + std::to_string(strain))) break;
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    try {
      for (const auto& [name, value] : dem::ucs_macro_values(result.curve)) result.macro[name] = value;
    } catch (const Error& e) {
      result.ok = false;
      result.reason = e.what();
    }
    if (result.ok && result.ended_by == "strain_limit") result.macro["reached_strain_limit"] = 1;
  }
  return result;
}

class UcsTest3D : public PackedSphereTest {
 public:
  std::string name() const override { return "ucs_3d"; }
  std::string description() const override {
    return "uniaxial compression of a sphere cylinder between two frictionless platens approaching at the loading "
           "velocity";
  }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-platen", kPlatenGroup, "the specimen's spheres against the loading platens"}};
  }
  std::vector<dem::OutputSpec> outputs(const Scene&) const override {
    return {
        {"sigma_u_MPa", "MPa", "peak axial stress (platen force / (pi D^2 / 4))", true, dem::kNonNegative},
        {"E_GPa", "GPa", "tangent Young's modulus where the stress first reaches half the peak (least squares over "
                         "a tenth of the points to the peak on each side)", true, dem::kNonNegative},
        {"E50_GPa", "GPa", "secant modulus at half the peak", true, dem::kNonNegative},
        {"nu", "1", "tangent Poisson's ratio d eps_lat / d eps_ax over the same window as E, the lateral strain the "
                    "least-squares radial strain of the lateral surface's spheres in the middle third", true,
         kPoissonRatio3D},
        {"nu50", "1", "secant Poisson's ratio eps_lat / eps_ax where the stress first reaches half the peak", true,
         kPoissonRatio3D},
        {"peak_strain", "1", "axial strain at the peak", true, dem::kNonNegative},
        {"reached_strain_limit", "1", "1 when the test ended at loading.strain_limit before the post-peak stop",
         false, dem::kFlag},
        {"cracks_tension", "1", "bonds broken in tension", true, dem::kNonNegative},
        {"cracks_shear", "1", "bonds broken in shear", true, dem::kNonNegative},
    };
  }
  void check_scene(const Scene& scene) const override {
    PackedSphereTest::check_scene(scene);
    if (sphere_specimen_spec(scene, scene.resolve({}), 1).vessel != Vessel::cylinder)
      throw Error(scene.origin() + ": specimen.shape: ucs_3d compresses a cylinder (\"shape\": \"cylinder\")");
  }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"sigma_u_MPa", "E_GPa", "nu"}; }
  std::vector<std::string> modulus_outputs(const Scene&) const override { return {"E_GPa", "E50_GPa"}; }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_ucs_3d(scene, parameters, options);
  }
};

}  // namespace

void register_ucs_test_3d(dem::LabTestRegistry& registry) { registry.add(std::make_unique<UcsTest3D>()); }

}  // namespace demcal::dem3d
