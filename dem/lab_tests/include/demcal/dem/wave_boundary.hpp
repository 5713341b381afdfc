#pragma once
// What the 2D wave tests (the wave strip, the slope) build their boundaries
// and records from (Ma et al. 2022, after Lysmer and Kuhlemeyer 1969): each
// side's type and dashpot coefficients, the equivalent continuum behind the
// dashpots, the cosine pulse, the replacement of a wall by its boundary, and
// the monitoring points' velocity records with their recovery times. Both
// tests read the same section keys with these, so a scene written for one
// reads alike in the other.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/dem/boundary_forces.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

class World;
struct Bodies;

// velocity: a fixed side whose disks move with the pulse's particle velocity
// and stand still once it has passed (Ma et al.'s fixed boundary, the pulse
// imposed on it): an input that reflects everything that comes back.
enum class BoundaryType { fixed, free, viscous, input, velocity };

// The length along the side each boundary disk's dashpot stands for: its
// diameter 2R (Ma et al.'s formula, which assumes the disks tile the side), or
// its tributary length (half the way to each neighbour along the side, the
// end disks out to the side's ends), which sums to the side's length whatever
// the packing, so the boundary's impedance does not change from specimen to specimen;
// or that length split between neighbours in proportion to their radii (where
// they would touch on the side), the same for equal disks, which gives a
// small disk between large ones (rockfill meeting bedrock on a slope's edge)
// a share of its own size rather than half the gap to a large neighbour.
enum class DashpotWidth { diameter, tributary, tributary_by_radius };
// Which continuum formula gives C_P from E_d and nu_d: Ma et al. 2022's,
// sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))) (plane strain, as they wrote it
// for their 2D model), or the plane-stress one of a 2D disk assembly,
// sqrt(E / (rho (1 - nu^2))), 4 % slower at nu 0.22. C_S is the same in both.
enum class PSpeedFormula { ma2022, plane_stress };

struct SideSpec {
  BoundaryType type = BoundaryType::free;
  double xi = 0, eta = 0;  // dashpot coefficients (viscous and input sides)
  DashpotWidth width = DashpotWidth::diameter;
  bool has_dashpots() const { return type == BoundaryType::viscous || type == BoundaryType::input; }
  bool carries_input() const { return type == BoundaryType::input || type == BoundaryType::velocity; }
};

// One side's object ({"type", "xi", "eta", "dashpot_width"}); `where` is
// "boundaries.left". Throws an Error naming the file and field.
SideSpec read_boundary_side(const Scene& scene, const std::map<std::string, double>& parameters,
                            const nlohmann::json& side, const std::string& where);

// The equivalent continuum behind the dashpots.
struct MediumSpec {
  double e_d_pa = 0, nu_d = 0;
  double given_p_speed_m_s = 0, given_s_speed_m_s = 0;  // > 0: used instead of the formulas
  PSpeedFormula p_formula = PSpeedFormula::ma2022;

  // C_P and C_S of the continuum of bulk density `rho` (given, or by the formulas
  // C_P = sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))), C_S = sqrt(E / (2 rho (1 + nu)))).
  double p_speed_m_s(double rho_kg_m3) const;
  double s_speed_m_s(double rho_kg_m3) const;
  double p_speed_formula_m_s(double rho_kg_m3) const;  // the chosen formula's
  double p_speed_ma2022_m_s(double rho_kg_m3) const;
  double p_speed_plane_stress_m_s(double rho_kg_m3) const;
  double s_speed_formula_m_s(double rho_kg_m3) const;
  // Reads {"E_d_Pa", "nu_d", "wave_speed_p_m_s", "wave_speed_s_m_s", "p_speed_formula"}
  // plus any of `extra_keys`; `where` names the object ("medium").
  static MediumSpec read(const Scene& scene, const std::map<std::string, double>& parameters,
                         const nlohmann::json& medium, const std::string& where,
                         const std::vector<std::string>& extra_keys = {});
};

// The cosine pulse v(t) = 0.5 A (1 - cos(2 pi t / T)) for t <= T, 0 after.
struct PulseSpec {
  double p_amplitude_m_s = 1, s_amplitude_m_s = 0, period_s = 0.2;
  static PulseSpec read(const Scene& scene, const std::map<std::string, double>& parameters,
                        const nlohmann::json& pulse, const std::string& where);
  static double cosine(double amplitude_m_s, double period_s, double time_s) {
    return time_s <= period_s ? 0.5 * amplitude_m_s * (1 - std::cos(2 * M_PI * time_s / period_s)) : 0.0;
  }
};

// The bulk density and wave speeds a boundary disk's dashpots use.
struct DiskImpedance {
  double rho_kg_m3 = 0, c_p_m_s = 0, c_s_m_s = 0;
};

// One side of the model, where a wall stood.
struct BoundarySide {
  std::size_t wall = 0;                // the wall it replaces, in world.walls
  std::string name;                    // "left", for messages and result keys
  std::array<double, 2> inward = {0, 0};  // unit normal into the model
  bool along_x = true;                 // the side runs along x (bottom, top) or along y
  // Its extent along that axis (the tributary widths' ends); to_m <= from_m: up to the far edge of the last
  // disk touching the wall (a side whose top is a free surface that settled).
  double from_m = 0, to_m = 0;
  // > 0: disks whose gap to the (axis-aligned) wall is at most this share of their radius join those touching it.
  double near_gap_fraction = 0;
};

struct BoundarySideSummary {
  std::size_t disks = 0;
  double covered_m = 0;   // sum of the boundary disks' diameters 2R
  double dashpot_m = 0;   // sum of the lengths their dashpots stand for
  double length_m = 0;    // the side's length the boundary stands for (to_m - from_m)
};

// Replaces `side`'s wall by its boundary (boundary_forces.hpp): every disk the
// wall touches (or nearly, side.near_gap_fraction) keeps the static force and
// moment the wall gives it now; a
// fixed or velocity side fixes them; viscous and input sides add dashpots
// c_n = w t xi rho C_P, c_s = w t eta rho C_S with w from `spec.width` and
// rho, C from `impedance` (per disk). The wall is made inactive. Throws an
// Error naming the file and "boundaries.<side>" when a dashpot would make the
// explicit update unstable (c dt / m > 1) or a non-free side touches no disk.
// Disks are added in id order, so the boundary's sums do not depend on storage.
BoundarySideSummary install_boundary_side(World& world, const BoundarySide& side, const SideSpec& spec,
                                          const std::function<DiskImpedance(std::size_t disk)>& impedance,
                                          BoundaryForces& boundary, const std::string& origin);

// The side's numbers in a result's specimen block: boundary_disks_<name>, boundary_coverage_<name> (the boundary
// disks' diameters over the side's length: Ma's 2R assumes about 1) and, for a side with dashpots,
// dashpot_coverage_<name> (what they stand for: the coverage with 2R, 1 with tributary lengths).
void record_boundary_side(TestResult& result, const std::string& name, const SideSpec& spec,
                          const BoundarySideSummary& summary);

// Runs `quiet_time_s` with no wave (the boundaries must hold the model where the walls did) and returns the
// largest move of a disk over it, m.
double run_quiet_period(World& world, double quiet_time_s);

// A point's recovery outputs (recovery_time_s_<label>, recovered_<label>); `below` says the threshold.
void add_recovery_outputs(std::vector<OutputSpec>& out, const std::string& label, const std::string& below);
// The energy outputs every wave test reports: energy_input_J, energy_absorbed_J, kinetic_energy_end_J.
void add_energy_outputs(std::vector<OutputSpec>& out);
// quiet_drift_m and quiet_force_ratio (whose ratio `ratio_of` names).
void add_quiet_outputs(std::vector<OutputSpec>& out, const std::string& ratio_of);

// A monitoring point: the free disks within its radius, whose mean velocity it records.
struct Monitor {
  std::string label;
  double x_m = 0, y_m = 0, distance_m = 0;  // distance_m: from the input face along the wave's path
  std::vector<std::size_t> disks;
  std::vector<double> vx, vy;
  // The free disks within `radius_m` of (x_m, y_m), in id order (only those of material group `group` when it
  // is 0-255); an Error naming `origin` when none.
  void collect(const Bodies& bodies, double radius_m, const std::string& origin, int group = -1);
  void record(const Bodies& bodies);
  std::vector<double> speeds() const;  // |v| per record
};

// The velocity records of a run: time, kinetic energy, each monitor's mean velocity.
struct WaveRecord {
  std::vector<Monitor> monitors;
  std::vector<double> times, kinetic;
  void record(const World& world);
  // time_s, kinetic_energy_J, then vx_<label>_m_s and vy_<label>_m_s per monitor.
  void add_series(TestResult& result) const;
};

// How run_recording steps a wave test's model.
struct RecordedRun {
  double end_time_s = 0;              // simulated time to run to
  std::uint64_t steps_per_record = 1;
  double max_speed_m_s = 100;         // a disk faster than this is unstable
  std::string max_speed_reason;       // why that speed ("100 x the pulse's amplitude")
  double max_wall_s = 600;            // wall time from `start` after which the run fails
  std::chrono::steady_clock::time_point start;
  std::string progress_label;
  bool show_progress = false;
  // Called after each record; true ends the run early (as done, not failed).
  std::function<bool()> done;
  bool record_first = true;  // false: the record already holds the present state (a resumed run)
};

// Records once, then steps `world` to run.end_time_s recording every
// run.steps_per_record steps. Sets result.ok; false with result.reason when
// the motion goes unstable (wave_instability) or the wall time runs out.
void run_recording(World& world, WaveRecord& record, const RecordedRun& run, TestResult& result);

// Empty while the motion is sane; otherwise why the run stops as failed
// (non-finite velocities, or a disk faster than `max_speed_m_s`, whose
// `reason` the message names).
std::string wave_instability(const Bodies& bodies, double time_s, double max_speed_m_s, const std::string& reason);

}  // namespace demcal::dem
