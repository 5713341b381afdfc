#include "demcal/dem3d/sphere_scene.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/dem/particle_order.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/material_pressure.hpp"
#include "demcal/dem3d/vtk_writer.hpp"

namespace demcal::dem3d {
namespace {

// How long a pressured specimen may take to come to rest out of its vessel.
constexpr std::uint64_t kRelaxationSteps = 200000;

}  // namespace

const dem::ContactModelCatalog& sphere_contact_models() {
  static const dem::RegistryCatalog<ContactModelRegistry> models("3d");
  return models;
}

void bind_contact_models(World& world, const Scene& scene, const std::map<std::string, double>& parameters,
                         bool frictionless) {
  for (const dem::ContactRole& role : scene.contact_roles()) {
    const dem::ContactSpec& c = scene.contacts().at(role.name);
    const std::string where = scene.origin() + ": contacts." + role.name;
    nlohmann::json bound = scene.bind(c, parameters, where);
    if (frictionless && bound.contains("friction")) bound["friction"] = 0.0;
    const std::uint8_t model = world.add_model(ContactModelRegistry::instance().create(c.model, bound, where));
    for (const auto& [a, b] : role.groups) world.assign(a, b, model);
  }
}

SphereSpecimenSpec sphere_specimen_spec(const Scene& scene, const std::map<std::string, double>& parameters,
                                        std::uint64_t seed) {
  const nlohmann::json& specimen = scene.section("specimen");
  const std::string where = scene.origin() + ": specimen";
  SphereSpecimenSpec spec;
  spec.vessel = choice_field(specimen, "shape", {"cylinder", "box"}, 0, where) == 0 ? Vessel::cylinder : Vessel::box;
  auto field = [&](const char* key, double& target) {
    if (specimen.contains(key)) target = scene.evaluate(specimen.at(key), parameters, where + "." + key);
  };
  if (spec.vessel == Vessel::cylinder) {
    if (specimen.contains("width_m") || specimen.contains("depth_m"))
      throw Error(where + ": a cylinder takes diameter_m and height_m (width_m and depth_m are a box's)");
    field("diameter_m", spec.width_m);
  } else {
    if (specimen.contains("diameter_m")) throw Error(where + ": a box takes width_m, depth_m and height_m");
    field("width_m", spec.width_m);
    field("depth_m", spec.depth_m);
  }
  field("height_m", spec.height_m);
  field("porosity", spec.porosity);
  field("radius_min_m", spec.radius_min_m);
  field("radius_max_m", spec.radius_max_m);
  field("density_kg_m3", spec.density_kg_m3);
  spec.seed = seed;
  return spec;
}

std::vector<dem::SceneSection> PackedSphereTest::sections() const {
  return {{"specimen", "the packed sphere specimen: its vessel (a cylinder or a box), radii, porosity and density", true,
           true, {}},
          {"loading", "how the test loads the specimen", false, false, {}}};
}

std::vector<dem::ContactRole> PackedSphereTest::specimen_roles(const Scene&) const {
  return {{"particle-particle", {{kSpecimenGroup, kSpecimenGroup}}, "the specimen's spheres against each other"}};
}

void PackedSphereTest::check_scene(const Scene& scene) const {
  require_known_fields(scene.section("specimen"),
                       {"shape", "diameter_m", "width_m", "depth_m", "height_m", "porosity", "radius_min_m",
                        "radius_max_m", "density_kg_m3", "locked_in_stress_pa", "note"},
                       scene.origin() + ": specimen");
  if (locked_in_stress_pa(scene, scene.resolve({})) > 0)
    for (const auto& [role, contact] : scene.contacts())
      if (contact.model == "flat_joint")  // its elements are installed force-free: the stress would have no carrier
        throw Error(scene.origin() + ": specimen.locked_in_stress_pa: not supported with the flat_joint model of contacts." +
                    role + " (its joints are installed force-free)");
  try {
    sphere_specimen_spec(scene, scene.resolve({}), 1).validate();
  } catch (const Error& e) {
    throw Error(scene.origin() + ": " + e.what());
  }
  const dem::LoadingSpec& loading = scene.loading();
  if (loading.elastic_speedup != 1)
    throw Error(scene.origin() + ": loading.elastic_speedup: the 3D tests load at one speed throughout");
  if (loading.platen_start != dem::LoadingSpec::PlatenStart::vessel_faces)
    throw Error(scene.origin() + ": loading.platen_start: the 3D tests start their platens at the vessel's faces");
}

std::vector<dem::SpecimenToPack> PackedSphereTest::specimens_to_pack(const Scene& scene,
                                                                     const std::map<std::string, double>& parameters,
                                                                     std::uint64_t seed) const {
  const SphereSpecimenSpec spec = sphere_specimen_spec(scene, parameters, seed);
  return {{spec.cache_key(), [spec](const std::string& cache_dir) { cached_sphere_specimen(spec, cache_dir); }}};
}

WorldSettings loading_settings(const dem::LoadingSpec& loading, const dem::RunOptions& options) {
  WorldSettings settings;
  settings.damping = loading.local_damping;
  settings.safety_factor = loading.safety_factor;
  settings.density_scaling_dt_s = loading.density_scaling_dt_s;
  if (options.threads > 0) settings.threads = options.threads;
  if (options.min_disks_per_thread > 0) settings.min_spheres_per_thread = options.min_disks_per_thread;
  return settings;
}

World specimen_world(const Scene& scene, const std::map<std::string, double>& parameters,
                     const SphereSpecimen& specimen, const dem::RunOptions& options,
                     const std::function<bool(Vec3& centre_m, double radius_m)>& admit, bool frictionless) {
  World world(loading_settings(scene.loading(), options));
  bind_contact_models(world, scene, parameters, frictionless);
  for (std::size_t k : dem::particle_order(specimen.size(), options.particle_order_seed)) {
    Vec3 centre{specimen.x[k], specimen.y[k], specimen.z[k]};
    if (admit && !admit(centre, specimen.radius[k])) continue;
    world.spheres.add_sphere(centre, specimen.radius[k], specimen.density_kg_m3, kSpecimenGroup,
                             static_cast<std::int64_t>(k));
  }
  return world;
}

std::string bond_specimen(World& world, const Scene& scene, const SphereSpecimen& specimen, std::uint64_t seed,
                          std::map<std::string, double>& info) {
  const dem::LoadingSpec& loading = scene.loading();
  const double r_min = *std::min_element(specimen.radius.begin(), specimen.radius.end());
  const double tolerance = loading.bond_gap_tolerance_m > 0 ? loading.bond_gap_tolerance_m : 0.01 * r_min;
  const bool pressured = specimen.locked_in_stress_pa > 0;
  // A pressured specimen's contacts keep their whole overlap's force (the locked-in fraction 1).
  const std::size_t bonds = world.install_bonds(tolerance, seed, pressured ? 1.0 : 0.0);
  info["coordination_number"] = specimen.coordination_number;
  info["mean_overlap_ratio"] = specimen.mean_overlap_ratio;
  info["bonds_per_sphere"] = 2.0 * static_cast<double>(bonds) / static_cast<double>(world.spheres.size());
  info["locked_in_stress_MPa"] = specimen.locked_in_stress_pa / 1e6;
  if (pressured) {
    const std::string failed = relax_out_of_vessel(world, kRelaxationSteps);
    if (!failed.empty()) return failed;
    info["locked_in_relaxation_steps"] = static_cast<double>(world.steps_done());
    info["locked_in_relaxation_breaks"] = static_cast<double>(world.breaks().size());
  }
  info["spheres_on_walls"] = static_cast<double>(world.make_wall_contacts_force_free());
  world.start_test();
  return "";
}

std::string SphereMonitoredWorld::instability(double platen_velocity_m_s) const {
  const Spheres& s = world_.spheres;
  const Wall &first = world_.walls[0], &second = world_.walls[1];
  double fastest2 = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3 v = s.velocity(i), x = s.position(i);
    fastest2 = std::max(fastest2, dot(v, v));
    if (!std::isfinite(x.x + x.y + x.z)) return "unstable: non-finite positions";
    // A platen's normal points into the specimen: a centre more than a radius behind it has passed through.
    if (dot(x - first.point_m, first.axis) < -s.radius[i] || dot(x - second.point_m, second.axis) < -s.radius[i])
      return "unstable: a sphere passed through a platen";
  }
  if (!std::isfinite(fastest2) || !std::isfinite(first.normal_force_n + second.normal_force_n))
    return "unstable: non-finite forces or velocities";
  if (fastest2 > 1e6 * platen_velocity_m_s * platen_velocity_m_s)
    return "unstable: a sphere moves faster than 1000 x the platen speed";
  return "";
}

void SphereMonitoredWorld::snapshot(const dem::RunOptions& options, std::size_t points, bool final) const {
  if (options.vtk_dir.empty()) return;
  const bool due =
      final || points == 1 || (options.vtk_every > 0 && points % static_cast<std::size_t>(options.vtk_every) == 0);
  if (!due) return;
  ::mkdir(options.vtk_dir.c_str(), 0755);
  char name[64];
  std::snprintf(name, sizeof(name), "%s_%06zu.vtk", final ? "final" : "spheres", points);
  write_vtk_spheres(world_, options.vtk_dir + "/" + name);
  std::snprintf(name, sizeof(name), "%s_%06zu.vtk", final ? "final_walls" : "walls", points);
  write_vtk_walls(world_, options.vtk_dir + "/" + name);
}

void record_run_end(const World& world, const dem::RunOptions& options, std::chrono::steady_clock::time_point start,
                    std::chrono::steady_clock::time_point loading_start, dem::TestResult& result) {
  const auto now = std::chrono::steady_clock::now();
  result.steps = world.steps_done();
  result.dt_s = world.dt_s();
  result.threads = world.threads_in_use();
  result.density_scaling_dt_s = world.settings().density_scaling_dt_s;
  SphereMonitoredWorld(world).snapshot(options, result.curve.size(), true);
  result.wall_s = std::chrono::duration<double>(now - start).count();
  result.test_wall_s = std::chrono::duration<double>(now - loading_start).count();
  std::size_t tension = 0;
  for (const dem::BreakEvent& b : world.breaks()) tension += b.mode == dem::BreakMode::Tension;
  result.macro["cracks_tension"] = static_cast<double>(tension);
  result.macro["cracks_shear"] = static_cast<double>(world.breaks().size() - tension);
}

}  // namespace demcal::dem3d
