#pragma once
// The peer run of `make bench`: a packed specimen released with fixed linear
// springs, no damping, no gravity and no walls (or fixed walls on its box),
// so its locked-in overlaps push the disks apart. The same run in LAMMPS (gran/hooke/history, 2D) is the
// yardstick of our speed, and the kinetic energy histories of the two say
// they did the same work (scripts/bench_lammps.sh).
#include <cstdint>

#include <nlohmann/json.hpp>

#include "demcal/dem/genesis.hpp"

namespace demcal::dem {

struct ReleasedRunOptions {
  double kn_n_m = 1e9, ks_n_m = 5e8, friction = 0.5;
  double dt_s = 0;                // required, > 0
  std::uint64_t steps = 20000;
  std::uint64_t every = 1000;     // kinetic energy every this many steps
  int threads = 0;                // 0: OpenMP's default
  // Four fixed walls on the specimen's box (the same springs): the packing
  // then stays nearly at rest, the load of a specimen between platens.
  bool box = false;
};

// {"disks", "width_m", "height_m", "density_kg_m3", "thickness_m", "steps", "dt_s", "skin_m", "threads", "rebuilds", "wall_s",
//  "particle_steps_per_s", "history": [[step, translational J, rotational J], ...]}
nlohmann::json run_released_specimen(const Specimen& specimen, const ReleasedRunOptions& options);

}  // namespace demcal::dem
