#include "demcal/dem/platen_test.hpp"

#include "demcal/dem/run_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/concrete_specimen.hpp"
#include "demcal/dem/equilibrium.hpp"
#include "demcal/dem/run_settings.hpp"
#include "demcal/dem/vtk_writer.hpp"

#include <sys/stat.h>

namespace demcal::dem {

BoundaryRole platen_role() { return {"particle-platen", kPlatenGroup, "the specimen's disks against the loading platens"}; }

std::vector<OutputSpec> platen_crack_outputs(const Scene& scene) {
  std::vector<OutputSpec> out = {{"cracks_tension", "1", "bonds broken in tension", true, kNonNegative},
                                 {"cracks_shear", "1", "bonds broken in shear", true, kNonNegative}};
  if (scene.has_section("aggregates")) {
    out.push_back({"cracks_mortar_tension", "1", "bonds broken in tension in the mortar", true, kNonNegative});
    out.push_back({"cracks_mortar_shear", "1", "bonds broken in shear in the mortar", true, kNonNegative});
    out.push_back({"cracks_itz_tension", "1", "bonds broken in tension in the interfacial transition zone", true,
                   kNonNegative});
    out.push_back({"cracks_itz_shear", "1", "bonds broken in shear in the interfacial transition zone", true,
                   kNonNegative});
  }
  return out;
}

World make_platen_world(const Scene& scene, const std::map<std::string, double>& parameters,
                        const Specimen& specimen, std::uint64_t seed, const std::vector<bool>* keep,
                        std::map<std::string, double>* info, bool side_walls, const std::pair<double, double>* faces_y,
                        const RunOptions* options) {
  WorldSettings settings;
  settings.thickness_m = specimen.thickness_m;
  settings.density_scaling_dt_s = scene.loading().density_scaling_dt_s;
  settings.damping = scene.loading().local_damping;
  settings.safety_factor = scene.loading().safety_factor;
  if (options) apply_run_options(settings, *options);
  World world(settings);
  bind_contact_models(world, scene, parameters);
  world.bodies.reserve(specimen.size());
  double bottom_y = INFINITY, top_y = -INFINITY, left_x = INFINITY, right_x = -INFINITY, r_min = INFINITY;
  for (const std::size_t i : particle_order(specimen.size(), options ? options->particle_order_seed : 0)) {
    if (keep && !(*keep)[i]) continue;
    world.bodies.add_disk(specimen.x[i], specimen.y[i], specimen.radius[i], specimen.density_kg_m3,
                          specimen.thickness_m, kSpecimenGroup, static_cast<std::int64_t>(i));
    bottom_y = std::min(bottom_y, specimen.y[i] - specimen.radius[i]);
    top_y = std::max(top_y, specimen.y[i] + specimen.radius[i]);
    left_x = std::min(left_x, specimen.x[i] - specimen.radius[i]);
    right_x = std::max(right_x, specimen.x[i] + specimen.radius[i]);
    r_min = std::min(r_min, specimen.radius[i]);
  }
  if (world.bodies.size() < 10) throw Error("the specimen holds fewer than 10 disks");
  if (const std::optional<AggregateSpec> aggregates = scene_aggregates(scene)) {
    const AggregateSpec& spec = *aggregates;
    AggregatePlacement placement = place_aggregates(spec, specimen.width_m, specimen.height_m, seed);
    AggregateSummary s = make_aggregate_clumps(world, placement, spec.density_kg_m3, specimen.thickness_m);
    if (info) {
      (*info)["aggregates_requested"] = s.requested;
      (*info)["aggregates_placed"] = s.placed;
      (*info)["aggregate_clumps"] = s.clumps;
      (*info)["aggregates_single_disk"] = s.single_disk;
      (*info)["aggregates_without_disks"] = s.without_disks;
      (*info)["aggregate_disks"] = static_cast<double>(s.aggregate_disks);
      (*info)["aggregate_area_fraction"] = s.area_fraction;
      (*info)["aggregate_area_fraction_target"] = s.target_area_fraction;
    }
  }

  // Bonds, with the contacts force-free as they lie unless the scene asks for
  // a locked-in stress: then each keeps the share of its overlap that gives
  // the contacts that mean stress at this point's stiffness.
  double solid_m2 = 0;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) solid_m2 += M_PI * world.bodies.radius[i] * world.bodies.radius[i];
  const double area_m2 = solid_m2 / (1 - specimen.porosity);  // the specimen's own, a Brazilian disc's too
  const double locked_in_pa = specimen_spec(scene, parameters, seed).locked_in_stress_pa;
  double locked_in_fraction = 0;
  if (locked_in_pa > 0) {
    for (const auto& [role, contact] : scene.contacts())
      if (contact.model == "flat_joint")  // its elements start force-free; the linear share it would keep is unused
        throw Error(scene.origin() + ": specimen.locked_in_stress_pa: not supported with the flat_joint model of contacts." +
                    role + " (its joints are installed force-free)");
    world.refresh();
    const double full_pa = contact_mean_stress_pa(world, area_m2);
    if (!(full_pa > locked_in_pa))
      throw Error(scene.origin() + ": specimen.locked_in_stress_pa " + format_double(locked_in_pa) +
                  " Pa is more than the packing's whole overlaps give at this stiffness (" + format_double(full_pa) + " Pa)");
    locked_in_fraction = locked_in_pa / full_pa;
  }
  const double tolerance = scene.loading().bond_gap_tolerance_m > 0 ? scene.loading().bond_gap_tolerance_m : 0.01 * r_min;
  const std::size_t bonds = world.install_bonds(tolerance, seed, locked_in_fraction);
  if (locked_in_fraction > 0) {
    // Out of the vessel, the specimen relaxes until the bonds hold the stress (PFC: remove the walls, equilibrate).
    if (!cycle_to_equilibrium(world, 1e-3, 200000))
      throw Error(scene.origin() + ": the specimen did not reach equilibrium after installing the locked-in stress");
    bottom_y = left_x = INFINITY;
    top_y = right_x = -INFINITY;
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
      bottom_y = std::min(bottom_y, world.bodies.y[i] - world.bodies.radius[i]);
      top_y = std::max(top_y, world.bodies.y[i] + world.bodies.radius[i]);
      left_x = std::min(left_x, world.bodies.x[i] - world.bodies.radius[i]);
      right_x = std::max(right_x, world.bodies.x[i] + world.bodies.radius[i]);
    }
    if (info) (*info)["locked_in_relaxation_breaks"] = static_cast<double>(world.breaks().size());
    world.start_test();
  }

  // A prism cut from nothing (no keep mask) and not relaxed out of its vessel
  // starts between the vessel's faces, as PFC's platens do.
  const bool vessel_faces = scene.loading().platen_start == LoadingSpec::PlatenStart::vessel_faces && !keep &&
                            locked_in_fraction == 0;
  if (vessel_faces) {
    bottom_y = 0;
    top_y = specimen.height_m;
    left_x = 0;
    right_x = specimen.width_m;
  }
  const bool given_faces = faces_y != nullptr && locked_in_fraction == 0;
  if (given_faces) {
    bottom_y = faces_y->first;
    top_y = faces_y->second;
  }
  const double W = specimen.width_m, v = scene.loading().platen_velocity_m_s;
  Wall bottom, top;
  bottom.x0 = top.x0 = -W;
  bottom.x1 = top.x1 = 2 * W;
  bottom.y0 = bottom.y1 = bottom_y;
  top.y0 = top.y1 = top_y;
  bottom.group = top.group = kPlatenGroup;
  bottom.vy = v;
  top.vy = -v;
  bottom.inward_ny = 1;
  top.inward_ny = -1;
  world.walls = {bottom, top};
  if (side_walls) {
    const double H = top_y - bottom_y;
    Wall left, right;
    left.y0 = right.y0 = bottom_y - H;
    left.y1 = right.y1 = top_y + H;
    left.x0 = left.x1 = left_x;
    right.x0 = right.x1 = right_x;
    left.group = right.group = kPlatenGroup;
    left.inward_nx = 1;
    right.inward_nx = -1;
    world.walls.push_back(left);
    world.walls.push_back(right);
  }
  if (vessel_faces || given_faces) {
    const std::size_t touching = world.make_wall_contacts_force_free();  // rebuilds the pairs with the platens
    if (info) (*info)["platen_contacts_at_start"] = static_cast<double>(touching);
  } else {
    world.refresh();
  }
  if (info) {
    // The packing as genesis left it (over the whole packed box) and this specimen's bonds and contact stress.
    (*info)["coordination_number"] = specimen.coordination_number;
    (*info)["mean_overlap_ratio"] = specimen.mean_overlap_ratio;
    (*info)["bonds_per_disk"] = 2.0 * static_cast<double>(bonds) / static_cast<double>(world.bodies.size());
    (*info)["locked_in_stress_MPa"] = contact_mean_stress_pa(world, area_m2) / 1e6;
  }
  return world;
}

std::string instability(const World& world, double platen_velocity_m_s) {
  const Bodies& b = world.bodies;
  double fastest = 0;
  for (std::size_t i = 0; i < b.size(); ++i) fastest = std::max(fastest, std::abs(b.vx[i]) + std::abs(b.vy[i]));
  if (!std::isfinite(fastest) || !std::isfinite(platen_force(world))) return "unstable: non-finite forces or velocities";
  // The platens span the domain: a disk beyond their ends, or through one, has
  // left it. Checked before the speed, since a test goes on past fast disks
  // when bonds are breaking (LoadingMonitor::record) but never past these.
  const Wall& bottom = world.wall(kBottomWall);
  const Wall& top = world.wall(kTopWall);
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.x[i] < bottom.x0 || b.x[i] > bottom.x1) return "unstable: a disk left the domain sideways";
    if (b.y[i] < bottom.y0 - b.radius[i] || b.y[i] > top.y0 + b.radius[i])
      return "unstable: a disk passed through a platen";
    if (world.walls.size() >= 4 &&
        (b.x[i] < world.wall(kLeftWall).x0 - b.radius[i] || b.x[i] > world.wall(kRightWall).x0 + b.radius[i]))
      return "unstable: a disk passed through a side wall";
  }
  if (fastest > 1000 * platen_velocity_m_s) return "unstable: a disk moves faster than 1000 x the platen speed";
  return "";
}

double platen_force(const World& world) { return 0.5 * (world.wall(kTopWall).fy - world.wall(kBottomWall).fy); }

void snapshot(const World& world, const RunOptions& options, std::size_t points, bool final) {
  if (options.vtk_dir.empty()) return;
  const bool due = final || points == 1 || (options.vtk_every > 0 && points % static_cast<std::size_t>(options.vtk_every) == 0);
  if (!due) return;
  ::mkdir(options.vtk_dir.c_str(), 0755);
  char name[64];
  std::snprintf(name, sizeof(name), "%s_%06zu.vtk", final ? "final" : "disks", points);
  write_vtk_disks(world, options.vtk_dir + "/" + name);
  std::snprintf(name, sizeof(name), "%s_%06zu.vtk", final ? "final_breaks" : "breaks", points);
  write_vtk_breaks(world, options.vtk_dir + "/" + name);
  std::snprintf(name, sizeof(name), "%s_%06zu.vtk", final ? "final_walls" : "walls", points);
  write_vtk_walls(world, options.vtk_dir + "/" + name);
}

void record_run_timing(const World& world, const RunOptions& options, std::chrono::steady_clock::time_point start,
                       std::chrono::steady_clock::time_point loading_start, TestResult& result) {
  const auto now = std::chrono::steady_clock::now();
  result.steps = world.steps_done();
  result.dt_s = world.dt_s();
  result.threads = world.threads_in_use();
  if (world.threads_in_use() > 1) result.thread_cuts = world.thread_cuts();
  result.density_scaling_dt_s = world.settings().density_scaling_dt_s;
  snapshot(world, options, result.curve.size(), true);
  result.wall_s = std::chrono::duration<double>(now - start).count();
  result.test_wall_s = std::chrono::duration<double>(now - loading_start).count();
}

void record_run_end(const World& world, const RunOptions& options, std::chrono::steady_clock::time_point start,
                    std::chrono::steady_clock::time_point loading_start, TestResult& result) {
  record_run_timing(world, options, start, loading_start, result);
  std::size_t tension = 0;
  for (const BreakEvent& b : world.breaks()) tension += b.mode == BreakMode::Tension;
  result.macro["cracks_tension"] = static_cast<double>(tension);
  result.macro["cracks_shear"] = static_cast<double>(world.breaks().size() - tension);
  if (!world.clumps().empty()) {
    // Concrete: cracks in the mortar and in the interfacial transition zone.
    std::size_t mortar_t = 0, mortar_s = 0, itz_t = 0, itz_s = 0;
    for (const BreakEvent& b : world.breaks()) {
      const bool itz = b.group_i == kAggregateGroup || b.group_j == kAggregateGroup;
      const bool t = b.mode == BreakMode::Tension;
      (itz ? (t ? itz_t : itz_s) : (t ? mortar_t : mortar_s))++;
    }
    result.macro["cracks_mortar_tension"] = static_cast<double>(mortar_t);
    result.macro["cracks_mortar_shear"] = static_cast<double>(mortar_s);
    result.macro["cracks_itz_tension"] = static_cast<double>(itz_t);
    result.macro["cracks_itz_shear"] = static_cast<double>(itz_s);
  }
}

}  // namespace demcal::dem
