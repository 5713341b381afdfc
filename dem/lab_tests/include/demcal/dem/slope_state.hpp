#pragma once
// What the slope test keeps in the cache (--cache), each file a key of what
// its content depends on and the content, written to a temporary file and
// renamed: the section at rest under gravity (read back by every run that
// shares it: a boundary calibration's candidates), and checkpoints of the wave
// run (read back by the same run started again). A file under another key is
// computed afresh; one whose key matched but that cannot be read fails the run.
#include <cstddef>
#include <map>
#include <string>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/slope_test.hpp"
#include "demcal/dem/test_result.hpp"
#include "demcal/dem/wave_boundary.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

// What the rest under gravity depends on: the section (the parts and profiles), the contact models as bound, the
// bond tolerance, gravity and the equilibrium's keys, the seed and the disks' order of entry; not the boundaries,
// the medium, the input or the monitors.
std::string slope_rest_key(const Scene& scene, const std::map<std::string, double>& parameters, const SlopeTestSpec& s,
                           const RunOptions& options);
// What sets a wave run's numbers beyond its rest: every section but the limits at which a run gives up (wall time,
// a disk's speed), which change nothing in a run that stays within them; and the parameters.
std::string wave_run_key(const Scene& scene, const std::map<std::string, double>& parameters);
// CACHE_DIR/PREFIX<hash of key>.bin
std::string cache_file(const std::string& cache_dir, const std::string& prefix, const std::string& key);

// True when `path` holds the rest state of `key` and the world now has it.
bool read_rest_state(World& world, const std::string& path, const std::string& key);
void write_rest_state(const World& world, const std::string& path, const std::string& key);

// The parts of a wave run a checkpoint carries besides the world: the boundary's work sums, the record so far,
// the disks taken out, whether the input's end was drawn.
struct WaveRunState {
  World& world;
  BoundaryForces& forces;
  WaveRecord& record;
  std::size_t& disks_out;
  bool& input_snapshot_done;
};

void write_wave_checkpoint(const std::string& path, const std::string& key, const WaveRunState& state);
// True when `path` holds a checkpoint of this run and the state now has it.
bool read_wave_checkpoint(const std::string& path, const std::string& key, WaveRunState& state);

}  // namespace demcal::dem
