// The 3D engine's side of `make bench` (scripts/bench_lammps_3d.py): packs (or
// loads from the cache) a 3D specimen, writes it as a LAMMPS data file, and
// runs it released (no walls) or in its box (six fixed planes) with fixed
// linear springs, Coulomb friction and no damping, as LAMMPS's
// gran/hooke/history runs it; prints JSON with the loop's wall time, the
// kinetic energy history and the peak memory. Not a stage of the chain: a
// measuring tool.
#include <sys/resource.h>

#include <chrono>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/genesis.hpp"
#include "demcal/dem3d/sphere_export.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

int main(int argc, char** argv) {
  CLI::App app{"bench_dem3d_released: a packed 3D specimen released or in its box, for the LAMMPS comparison"};
  SphereSpecimenSpec spec;
  std::string cache, lammps, vessel = "box";
  double kn = 0, ks = 0, friction = 0.5, dt = 0, skin = 0;
  std::uint64_t steps = 1000, every = 100;
  int threads = 1;
  bool box = false, pack_only = false;
  app.add_option("--vessel", vessel, "box or cylinder")->check(CLI::IsMember({"box", "cylinder"}));
  app.add_option("--width", spec.width_m, "m (a cylinder's diameter)");
  app.add_option("--depth", spec.depth_m, "m");
  app.add_option("--height", spec.height_m, "m");
  app.add_option("--radius-min", spec.radius_min_m, "m");
  app.add_option("--radius-max", spec.radius_max_m, "m");
  app.add_option("--porosity", spec.porosity);
  app.add_option("--seed", spec.seed);
  app.add_option("--cache", cache, "folder of cached packings");
  app.add_option("--lammps", lammps, "write the specimen as a LAMMPS data file and stop");
  app.add_flag("--pack-only", pack_only, "pack (or load) the specimen, print its size and stop");
  app.add_option("--kn", kn, "N/m");
  app.add_option("--ks", ks, "N/m");
  app.add_option("--friction", friction);
  app.add_option("--dt", dt, "s");
  app.add_option("--skin", skin, "m (0: a quarter of the mean radius)");
  app.add_option("--steps", steps);
  app.add_option("--every", every, "steps between kinetic energy records");
  app.add_option("--threads", threads);
  app.add_flag("--box", box, "six fixed planes at the vessel's faces (a box vessel only)");
  CLI11_PARSE(app, argc, argv);
  try {
    spec.vessel = vessel == "box" ? Vessel::box : Vessel::cylinder;
    const auto pack_start = std::chrono::steady_clock::now();
    const SphereSpecimen s = cached_sphere_specimen(spec, cache);
    const double pack_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - pack_start).count();
    if (!lammps.empty() || pack_only) {
      if (!lammps.empty()) write_lammps_data(s, lammps, "bench_dem3d_released, seed " + std::to_string(spec.seed));
      std::cout << nlohmann::json{{"spheres", s.size()}, {"porosity", s.porosity}, {"pack_s", pack_s},
                                  {"coordination_number", s.coordination_number}}
                << "\n";
      return 0;
    }
    if (!(kn > 0) || !(ks > 0) || !(dt > 0)) throw demcal::Error("--kn, --ks and --dt must be > 0");
    if (box && spec.vessel != Vessel::box) throw demcal::Error("--box needs --vessel box");
    WorldSettings settings;
    settings.damping = 0;
    settings.fixed_dt_s = dt;
    settings.skin_m = skin;
    settings.threads = threads;
    World world(settings);
    const std::uint8_t model = world.add_model(ContactModelRegistry::instance().create(
        "linear", {{"kn_n_m", kn}, {"ks_n_m", ks}, {"friction", friction}}, "bench"));
    world.assign(0, 0, model);
    world.assign(0, 1, model);
    for (std::size_t i = 0; i < s.size(); ++i)
      world.spheres.add_sphere({s.x[i], s.y[i], s.z[i]}, s.radius[i], s.density_kg_m3, 0, static_cast<std::int64_t>(i));
    if (box) {
      world.walls.push_back(make_plane({0, 0, 0}, {1, 0, 0}));
      world.walls.push_back(make_plane({s.width_m, 0, 0}, {-1, 0, 0}));
      world.walls.push_back(make_plane({0, 0, 0}, {0, 1, 0}));
      world.walls.push_back(make_plane({0, s.depth_m, 0}, {0, -1, 0}));
      world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}));
      world.walls.push_back(make_plane({0, 0, s.height_m}, {0, 0, -1}));
    }
    world.refresh();
    nlohmann::json history = nlohmann::json::array();
    auto record = [&]() {
      double translational = 0, rotational = 0;
      // In id order (the world's storage order changes).
      std::vector<std::size_t> by_id(world.spheres.size());
      for (std::size_t i = 0; i < by_id.size(); ++i) by_id[world.spheres.id[i]] = i;
      for (std::size_t i : by_id) {
        const Vec3 v = world.spheres.velocity(i), w = world.spheres.spin(i);
        translational += 0.5 * world.spheres.mass[i] * dot(v, v);
        rotational += 0.5 * world.spheres.inertia[i] * dot(w, w);
      }
      history.push_back({world.steps_done(), translational, rotational});
    };
    record();
    double loop_s = 0;
    for (std::uint64_t done = 0; done < steps; done += every) {
      const auto start = std::chrono::steady_clock::now();
      world.run(std::min(every, steps - done));
      loop_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      record();
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::cout << nlohmann::json{{"spheres", s.size()},
                                {"steps", world.steps_done()},
                                {"wall_s", loop_s},
                                {"threads", world.threads_in_use()},
                                {"skin_m", world.skin_m()},
                                {"density_kg_m3", s.density_kg_m3},
                                {"width_m", s.width_m},
                                {"depth_m", s.depth_m},
                                {"height_m", s.height_m},
                                {"rebuilds", world.rebuilds()},
                                {"peak_rss_kib", usage.ru_maxrss},
                                {"history", history}}
              << "\n";
  } catch (const std::exception& e) {
    std::cerr << "bench_dem3d_released: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
