#include "released_run.hpp"

#include <chrono>

#include "demcal/core/error.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

namespace {

double translational_energy(const Bodies& b) {
  double e = 0;
  for (std::size_t i = 0; i < b.size(); ++i) e += 0.5 * b.mass[i] * (b.vx[i] * b.vx[i] + b.vy[i] * b.vy[i]);
  return e;
}

}  // namespace

nlohmann::json run_released_specimen(const Specimen& s, const ReleasedRunOptions& o) {
  if (!(o.dt_s > 0)) throw Error("--dt must be positive");
  if (o.every == 0) throw Error("--every must be at least 1");
  WorldSettings settings;
  settings.thickness_m = s.thickness_m;
  settings.damping = 0.0;
  settings.fixed_dt_s = o.dt_s;
  settings.threads = o.threads;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(
                         "linear", {{"kn_n_m", o.kn_n_m}, {"ks_n_m", o.ks_n_m}, {"friction", o.friction}},
                         "released run")));
  world.bodies.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    world.bodies.add_disk(s.x[i], s.y[i], s.radius[i], s.density_kg_m3, s.thickness_m, 0,
                          static_cast<std::int64_t>(i));
  if (o.box) {
    // Segments longer than the sides, so no disk slips out at a corner.
    const double w = s.width_m, h = s.height_m;
    const double sides[4][4] = {{-w, 0, 2 * w, 0}, {-w, h, 2 * w, h}, {0, -h, 0, 2 * h}, {w, -h, w, 2 * h}};
    for (const auto& e : sides) {
      Wall wall;
      wall.x0 = e[0];
      wall.y0 = e[1];
      wall.x1 = e[2];
      wall.y1 = e[3];
      wall.group = 1;
      world.walls.push_back(wall);
    }
    world.assign(0, 1, 0);
  }
  world.refresh();

  nlohmann::json history = nlohmann::json::array();
  double run_s = 0;
  for (std::uint64_t done = 0; done < o.steps;) {
    const std::uint64_t chunk = std::min(o.every, o.steps - done);
    const auto start = std::chrono::steady_clock::now();
    world.run(chunk);
    run_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    done += chunk;
    const double translational = translational_energy(world.bodies);
    history.push_back({done, translational, world.kinetic_energy() - translational});
  }
  return {{"disks", s.size()},
          {"width_m", s.width_m},
          {"height_m", s.height_m},
          {"density_kg_m3", s.density_kg_m3},
          {"thickness_m", s.thickness_m},
          {"steps", o.steps},
          {"dt_s", world.dt_s()},
          {"skin_m", world.skin_m()},  // the engine's default, stated so LAMMPS can use the same
          {"threads", world.threads_in_use()},
          {"rebuilds", world.rebuilds()},
          {"wall_s", run_s},
          {"particle_steps_per_s", run_s > 0 ? static_cast<double>(s.size()) * static_cast<double>(o.steps) / run_s : 0.0},
          {"history", history}};
}

}  // namespace demcal::dem
