#pragma once
// What the platen tests (uniaxial compression, Brazilian disc) share: the
// world of a specimen between two platens that approach each other, bonds
// installed, and the checks that tell a run has gone unstable.
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "demcal/core/progress.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

constexpr std::uint8_t kSpecimenGroup = 0, kPlatenGroup = 1;

// The platens' contact role: "particle-platen", every specimen group against the platens.
BoundaryRole platen_role();
// The crack counts every platen test reports (by mode; a concrete also by phase).
std::vector<OutputSpec> platen_crack_outputs(const Scene& scene);

// Disks of `specimen` (only those with keep[i] when `keep` is given), the
// scene's contact models, bonds on every pair closer than the scene's
// tolerance with every overlapping pair force-free as it lies, and a bottom
// and a top platen moving towards each other at the loading velocity. A
// prism's platens start at its vessel's faces, touching every disk that
// touched the vessel with no force (loading.platen_start); a disc cut by
// `keep`, or a relaxed locked-in specimen, has them touch its lowest and
// highest disk. Walls: [0] bottom, [1] top.
// A scene with aggregates also places them (seeded by `seed`), makes their
// clumps and binds the mortar, interface and aggregate contacts. With
// specimen.locked_in_stress_pa the contacts keep that mean stress instead and
// the specimen relaxes, without walls, until the bonds hold it; the test's
// counters start after that. `info`, when given, receives what the specimen
// holds (aggregates placed, disks in them, the packing's coordination number
// and overlaps, bonds per disk, the contacts' locked-in stress, the disks
// touching the platens at the start when they start at the vessel's faces).
// With `side_walls` (the biaxial test) two vertical walls of the platens'
// group confine the sides, placed like the platens: at the vessel's side
// faces or at the outermost disks; walls [2] left, [3] right. Every wall then
// carries its inward normal (for a stress servo).
// `faces_y` (bottom, top), when given, places the platens there instead, the
// disks crossing them touching with no force (a Brazilian disc's flats).
// `options`, when given, sets the world's threads and the disks' order of entry
// (run_settings.hpp).
World make_platen_world(const Scene& scene, const std::map<std::string, double>& parameters,
                        const Specimen& specimen, std::uint64_t seed, const std::vector<bool>* keep = nullptr,
                        std::map<std::string, double>* info = nullptr, bool side_walls = false,
                        const std::pair<double, double>* faces_y = nullptr, const RunOptions* options = nullptr);

// Empty when the state is sane; otherwise why the run must stop as failed
// (non-finite values, a disk faster than 1000 x the platen speed, a disk
// beyond the platens' ends or through a platen or a side wall).
std::string instability(const World& world, double platen_velocity_m_s);

// Mean force the disks exert on the two platens, compression positive, N.
double platen_force(const World& world);

// Writes VTK snapshots into options.vtk_dir at the first curve point, every
// options.vtk_every points and at the end (`final`); nothing when unset.
void snapshot(const World& world, const RunOptions& options, std::size_t points, bool final);

// The disk world as the loading monitor (loading_monitor.hpp) sees it.
class DiskMonitoredWorld : public MonitoredWorld {
 public:
  explicit DiskMonitoredWorld(const World& world) : world_(world) {}
  std::string instability(double platen_velocity_m_s) const override {
    return dem::instability(world_, platen_velocity_m_s);
  }
  double kinetic_energy_j() const override { return world_.kinetic_energy(); }
  std::size_t breaks() const override { return world_.breaks().size(); }
  void snapshot(const RunOptions& options, std::size_t points, bool final) const override {
    dem::snapshot(world_, options, points, final);
  }

 private:
  const World& world_;
};

// Fills in what every run reports at its end: steps, time step, threads, wall
// times (whole run since `start`, loading since `loading_start`), and writes
// the final VTK snapshot when asked for.
void record_run_timing(const World& world, const RunOptions& options, std::chrono::steady_clock::time_point start,
                       std::chrono::steady_clock::time_point loading_start, TestResult& result);
// record_run_timing and the platen tests' crack counts by mode (and, for a
// concrete, by phase).
void record_run_end(const World& world, const RunOptions& options, std::chrono::steady_clock::time_point start,
                    std::chrono::steady_clock::time_point loading_start, TestResult& result);

}  // namespace demcal::dem
