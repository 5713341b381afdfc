#include "powder_run.hpp"

#include <sys/stat.h>

#include <cmath>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/dem/cohesion_number.hpp"
#include "demcal/dem3d/sphere_scene.hpp"
#include "demcal/dem3d/vtk_writer.hpp"

namespace demcal::dem3d {

PowderSpec3d read_powder_section(const dem::Scene& scene, const std::map<std::string, double>& parameters) {
  PowderSpec3d powder;
  const nlohmann::json& p = scene.section("particles");
  require_known_fields(p, {"radius_min_m", "radius_max_m", "density_kg_m3", "clump_aspect_ratio", "clump_fraction",
                           "note"},
                       scene.origin() + ": particles");
  auto number = [&](const char* key, double& target, bool required) {
    dem::read_section_number(scene, parameters, "particles", p, key, target, required);
  };
  number("radius_min_m", powder.radius_min_m, true);
  number("radius_max_m", powder.radius_max_m, true);
  number("density_kg_m3", powder.density_kg_m3, true);
  number("clump_aspect_ratio", powder.clump_aspect_ratio, false);
  number("clump_fraction", powder.clump_fraction, false);
  return powder;
}

double potential_energy_j(const World& world, double floor_z) {
  double energy = 0;
  for (const Clump& c : world.clumps()) energy += c.mass_kg * kPowderGravity_m_s2 * (c.centre_m.z - floor_z);
  const Spheres& s = world.spheres;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.clump[i] < 0 && !s.fixed[i]) energy += s.mass[i] * kPowderGravity_m_s2 * (s.z[i] - floor_z);
  return energy;
}

const std::vector<std::string>& PowderStepping::keys() {
  static const std::vector<std::string> names = {"local_damping", "safety_factor", "rayleigh_fraction"};
  return names;
}

void PowderStepping::read(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                          const nlohmann::json& run) {
  dem::read_section_number(scene, parameters, "run", run, "local_damping", local_damping, false);
  dem::read_section_number(scene, parameters, "run", run, "safety_factor", safety_factor, false);
  dem::read_section_number(scene, parameters, "run", run, "rayleigh_fraction", rayleigh_fraction, false);
  const std::string rw = scene.origin() + ": run";
  if (!(local_damping >= 0 && local_damping < 1)) throw Error(rw + ".local_damping must lie in [0, 1)");
  if (!(safety_factor > 0 && safety_factor <= 1)) throw Error(rw + ".safety_factor must lie in (0, 1]");
  if (!(rayleigh_fraction >= 0 && rayleigh_fraction <= 0.5))
    throw Error(rw + ".rayleigh_fraction must lie in [0, 0.5] (0: the engine's step from the contacts' stiffness)");
}

double rayleigh_step_s(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                       const PowderSpec3d& powder) {
  auto it = scene.contacts().find("particle-particle");
  if (it == scene.contacts().end()) return 0;
  const nlohmann::json bound = scene.bind(it->second, parameters, scene.origin() + ": contacts.particle-particle");
  if (!bound.contains("shear_modulus_pa") || !bound.contains("poisson")) return 0;
  const double g = bound.at("shear_modulus_pa").get<double>(), nu = bound.at("poisson").get<double>();
  return M_PI * powder.radius_min_m * std::sqrt(powder.density_kg_m3 / g) / (0.1631 * nu + 0.8766);
}

WorldSettings powder_settings(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                              const PowderSpec3d& powder, const PowderStepping& stepping,
                              const dem::RunOptions& options) {
  WorldSettings settings;
  settings.damping = stepping.local_damping;
  settings.safety_factor = stepping.safety_factor;
  settings.gravity_m_s2 = {0, 0, -kPowderGravity_m_s2};
  if (options.threads > 0) settings.threads = options.threads;
  if (options.min_disks_per_thread > 0) settings.min_spheres_per_thread = options.min_disks_per_thread;
  if (stepping.rayleigh_fraction > 0) {
    const double rayleigh_s = rayleigh_step_s(scene, parameters, powder);
    if (!(rayleigh_s > 0))
      throw Error(scene.origin() + ": run.rayleigh_fraction needs a Hertz material (shear_modulus_pa, poisson) in "
                  "contacts.particle-particle");
    // A run whose fixed step is too large for its contacts fails as unstable (each test checks its particles).
    settings.fixed_dt_s = stepping.rayleigh_fraction * rayleigh_s;
  }
  return settings;
}

void report_powder_contacts(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                            const PowderSpec3d& powder, double dt_s, dem::TestResult& result) {
  auto it = scene.contacts().find("particle-particle");
  if (it == scene.contacts().end()) return;
  const double rayleigh_s = rayleigh_step_s(scene, parameters, powder);
  if (!(rayleigh_s > 0)) return;
  result.specimen_info["dt_over_rayleigh_step"] = dt_s / rayleigh_s;
  if (it->second.model != "jkr") return;
  const nlohmann::json bound = scene.bind(it->second, parameters, scene.origin() + ": contacts.particle-particle");
  const double g = bound.at("shear_modulus_pa").get<double>(), nu = bound.at("poisson").get<double>();
  const double w = bound.at("work_of_adhesion_j_m2").get<double>();
  const double r_star = 0.25 * (powder.radius_min_m + powder.radius_max_m);  // two particles of the mean radius
  result.specimen_info["work_of_adhesion_j_m2"] = w;
  result.specimen_info["cohesion_number"] =
      dem::cohesion_number(w, dem::effective_modulus_pa(g, nu), r_star, powder.density_kg_m3, kPowderGravity_m_s2);
}

void finish_powder_run(const World& world, const dem::Scene& scene, const std::map<std::string, double>& parameters,
                       const PowderSpec3d& powder, const dem::RunOptions& options,
                       std::chrono::steady_clock::time_point start,
                       std::chrono::steady_clock::time_point loading_start, dem::TestResult& result) {
  const auto now = std::chrono::steady_clock::now();
  result.steps = world.steps_done();
  result.dt_s = world.dt_s();
  report_powder_contacts(scene, parameters, powder, world.dt_s(), result);
  result.threads = world.threads_in_use();
  result.wall_s = std::chrono::duration<double>(now - start).count();
  result.test_wall_s = std::chrono::duration<double>(now - loading_start).count();
  if (!options.vtk_dir.empty()) {
    ::mkdir(options.vtk_dir.c_str(), 0755);
    write_vtk_spheres(world, options.vtk_dir + "/final_000000.vtk");
    write_vtk_walls(world, options.vtk_dir + "/final_walls_000000.vtk");
  }
}

const dem::ContactModelCatalog& PowderTest3d::contact_models() const { return sphere_contact_models(); }

std::vector<dem::ContactRole> PowderTest3d::specimen_roles(const dem::Scene&) const {
  return {{"particle-particle", {{kPowderGroup, kPowderGroup}}, "particles against each other"}};
}

}  // namespace demcal::dem3d
