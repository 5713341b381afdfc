// Direct tension of a sphere cylinder (PFC3D's direct-tension test): the
// spheres whose centres lie within the grip length of either end face are
// driven apart along the axis, each end at the loading velocity, and the rest
// follows through its bonds. The stress is the force the gauge part holds the
// grips back with over the section (pi D^2 / 4), the strain the grips'
// separation over the gauge length between them; the strength is the peak.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"
#include "demcal/dem3d/material_pressure.hpp"
#include "demcal/dem3d/sphere_scene.hpp"

namespace demcal::dem3d {
namespace {

constexpr std::size_t kBottom = 0, kTop = 1;

// The grip length: grips.length_m, or two of the largest sphere's diameters.
double grip_length_m(const Scene& scene, const std::map<std::string, double>& parameters) {
  const nlohmann::json& grips = scene.section("grips");
  if (!grips.contains("length_m")) return 4 * sphere_specimen_spec(scene, parameters, 1).radius_max_m;
  double length = 0;
  dem::read_section_number(scene, parameters, "grips", grips, "length_m", length, true);
  if (!(length > 0)) throw Error(scene.origin() + ": grips.length_m must be positive");
  return length;
}

// One grip: its spheres' ids in ascending order, so the force on it is summed
// in an order the state alone sets (the world reorders its arrays).
class Grip {
 public:
  Grip(const Spheres& s, bool top, double bottom_z, double top_z, double length_m) {
    for (std::size_t i = 0; i < s.size(); ++i)
      if (top ? s.z[i] > top_z - length_m : s.z[i] < bottom_z + length_m) ids_.push_back(s.id[i]);
    std::sort(ids_.begin(), ids_.end());
  }
  std::size_t size() const { return ids_.size(); }
  void drive(World& w, double vz_m_s) const {
    const std::vector<std::uint32_t> index = index_by_id(w);
    for (std::uint32_t id : ids_) {
      const std::uint32_t i = index[id];
      w.spheres.fixed[i] = 1;
      w.spheres.set_velocity(i, {0, 0, vz_m_s});
      w.spheres.set_spin(i, {});
    }
  }
  // The axial force the rest of the specimen pulls the grip with, N.
  double axial_force_n(const World& w) const {
    const std::vector<std::uint32_t> index = index_by_id(w);
    double f = 0;
    for (std::uint32_t id : ids_) f += w.contact_force(index[id]).z;
    return f;
  }

 private:
  static std::vector<std::uint32_t> index_by_id(const World& w) {
    const Spheres& s = w.spheres;
    std::uint32_t end = 0;
    for (std::uint32_t id : s.id) end = std::max(end, id + 1);
    std::vector<std::uint32_t> index(end, UINT32_MAX);
    for (std::size_t i = 0; i < s.size(); ++i) index[s.id[i]] = static_cast<std::uint32_t>(i);
    return index;
  }
  std::vector<std::uint32_t> ids_;
};

dem::TestResult run_direct_tension_3d(const Scene& scene, const std::map<std::string, double>& parameters,
                                      const dem::RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const dem::LoadingSpec& loading = scene.loading();
  dem::TestResult result;
  SphereSpecimen specimen;
  if (!test_specimen(scene, parameters, options, result, specimen)) return result;

  World world = specimen_world(scene, parameters, specimen, options);
  // The end faces, as the compression test's platens: a pressured specimen relaxes out of them and they are set
  // back where they touch it. They then carry nothing and move with the grips, marking the specimen's ends.
  world.walls = {make_plane({0, 0, 0}, {0, 0, 1}, kPlatenGroup),
                 make_plane({0, 0, specimen.height_m}, {0, 0, -1}, kPlatenGroup)};
  result.reason = bond_specimen(world, scene, specimen, options.seed, result.specimen_info);
  if (!result.reason.empty()) return result;

  const double bottom_z = world.walls[kBottom].point_m.z, top_z = world.walls[kTop].point_m.z;
  const double D = specimen.width_m, H0 = top_z - bottom_z, area = 0.25 * M_PI * D * D;
  const double grip = grip_length_m(scene, parameters), gauge = H0 - 2 * grip;
  if (!(gauge >= 0.5 * H0)) {
    result.reason = "grips.length_m " + format_double(grip) + " m leaves a gauge shorter than half the specimen (" +
                    format_double(H0) + " m high)";
    return result;
  }
  const Grip bottom(world.spheres, false, bottom_z, top_z, grip), top(world.spheres, true, bottom_z, top_z, grip);
  if (bottom.size() < 8 || top.size() < 8) {
    result.reason = "a grip holds fewer than 8 spheres: grips.length_m " + format_double(grip) + " m is too short";
    return result;
  }
  const double v = loading.platen_velocity_m_s;
  bottom.drive(world, -v);
  top.drive(world, v);
  for (Wall& w : world.walls) w.active = false;
  world.walls[kBottom].velocity_m_s = {0, 0, -v};
  world.walls[kTop].velocity_m_s = {0, 0, v};
  result.particles = specimen.size();
  result.porosity = specimen.porosity;
  result.specimen_info["grip_spheres"] = static_cast<double>(bottom.size() + top.size());
  result.specimen_info["gauge_length_m"] = gauge;

  const auto loading_start = std::chrono::steady_clock::now();
  dem::LoadingMonitor monitor(loading, options, start, area * gauge);
  double next_record = 0;
  for (;;) {
    world.step();
    const double strain = (world.walls[kTop].point_m.z - world.walls[kBottom].point_m.z - H0) / gauge;
    if (strain < next_record) continue;
    next_record = strain + loading.record_strain;
    dem::CurvePoint point;
    point.axial_strain = strain;
    point.stress_pa = 0.5 * (bottom.axial_force_n(world) - top.axial_force_n(world)) / area;
    point.cracks = world.breaks().size();
    if (!monitor.record(SphereMonitoredWorld(world), point, result, "axial strain " + std::to_string(strain))) break;
  }
  record_run_end(world, options, start, loading_start, result);
  if (result.ok) {
    try {
      const std::map<std::string, double> values = dem::ucs_macro_values(result.curve);
      result.macro["sigma_t_direct_MPa"] = values.at("sigma_u_MPa");
      result.macro["E_tension_GPa"] = values.at("E_GPa");
      result.macro["peak_strain"] = values.at("peak_strain");
    } catch (const Error& e) {
      result.ok = false;
      result.reason = e.what();
    }
    if (result.ok && result.ended_by == "strain_limit") result.macro["reached_strain_limit"] = 1;
  }
  return result;
}

class DirectTensionTest3D : public PackedSphereTest {
 public:
  std::string name() const override { return "direct_tension_3d"; }
  std::string description() const override {
    return "direct tension of a sphere cylinder: the spheres within a grip length of each end are pulled apart along "
           "the axis at the loading velocity";
  }
  std::vector<dem::SceneSection> sections() const override {
    std::vector<dem::SceneSection> s = PackedSphereTest::sections();
    s.push_back({"grips", "how much of each end the grips hold", false, false, {}});
    return s;
  }
  std::vector<dem::BoundaryRole> boundary_roles() const override {
    return {{"particle-platen", kPlatenGroup,
             "the specimen's spheres against the vessel's end faces while a material pressure is installed (the "
             "test pulls by grips, not platens)"}};
  }
  std::vector<dem::OutputSpec> outputs(const Scene&) const override {
    return {
        {"sigma_t_direct_MPa", "MPa", "direct tensile strength: the peak axial force on the grips / (pi D^2 / 4)", true,
         dem::kNonNegative},
        {"E_tension_GPa", "GPa", "tangent Young's modulus in tension where the stress first reaches half the peak "
                                 "(the compression test's window), the strain over the gauge between the grips",
         true, dem::kNonNegative},
        {"peak_strain", "1", "axial strain of the gauge at the peak", true, dem::kNonNegative},
        {"reached_strain_limit", "1", "1 when the test ended at loading.strain_limit before the post-peak stop",
         false, dem::kFlag},
        {"cracks_tension", "1", "bonds broken in tension", true, dem::kNonNegative},
        {"cracks_shear", "1", "bonds broken in shear", true, dem::kNonNegative},
    };
  }
  void check_scene(const Scene& scene) const override {
    PackedSphereTest::check_scene(scene);
    const std::map<std::string, double> defaults = scene.resolve({});
    if (sphere_specimen_spec(scene, defaults, 1).vessel != Vessel::cylinder)
      throw Error(scene.origin() + ": specimen.shape: direct_tension_3d pulls a cylinder (\"shape\": \"cylinder\")");
    require_known_fields(scene.section("grips"), {"length_m", "note"}, scene.origin() + ": grips");
    grip_length_m(scene, defaults);
  }
  std::vector<std::string> headline_outputs(const Scene&) const override { return {"sigma_t_direct_MPa"}; }
  std::vector<std::string> modulus_outputs(const Scene&) const override { return {"E_tension_GPa"}; }
  std::pair<std::string, std::string> curve_axes() const override {
    return {"axial strain of the gauge", "axial force on the grips / (pi D^2 / 4) (MPa)"};
  }
  dem::TestResult run(const Scene& scene, const std::map<std::string, double>& parameters,
                      const dem::RunOptions& options) const override {
    return run_direct_tension_3d(scene, parameters, options);
  }
};

}  // namespace

void register_direct_tension_test_3d(dem::LabTestRegistry& registry) {
  registry.add(std::make_unique<DirectTensionTest3D>());
}

}  // namespace demcal::dem3d
