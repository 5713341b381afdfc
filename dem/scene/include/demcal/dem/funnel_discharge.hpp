#pragma once
// The stages of a funnel heap, in 2D or 3D: the gate stays shut while the
// powder settles in the funnel (run.fill_time_s); the funnel discharges until
// all but (1 - run.discharged_fraction) of its particles have left it (a jam
// when none leaves for run.jam_time_s); then the heap settles until its
// kinetic energy falls below run.settle_kinetic_ratio of its potential energy
// above the catch floor. The test steps its world and asks `check` every
// run.check_every_s; what it counts and weighs is its own (disks or spheres).
#include <chrono>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/dem/run_watch.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// The "run" keys of the stages: a settling run's (run_watch.hpp) and the discharge's.
struct FunnelRun : SettleRun {
  double jam_time_s = 0.5, discharged_fraction = 0.95;

  static const std::vector<std::string>& keys();
  void read(const Scene& scene, const std::map<std::string, double>& parameters, const nlohmann::json& run);
  void validate(const std::string& where) const;
};

// How a failure names the test's particles and the outlet's size key.
struct FunnelWords {
  std::string test;        // "heap", for the timeout
  std::string label;       // "heap_3d", heading the progress line
  std::string particles;   // "particles" or "spheres"
  std::string outlet_key;  // "funnel.outlet_width_m"
};

class FunnelDischarge {
 public:
  enum class Next { step_on, open_gate, settled, failed };

  // `total`: the particles in the funnel at the start; `start`: when the run began (run.max_wall_s counts from it).
  FunnelDischarge(const FunnelRun& run, std::size_t total, FunnelWords words,
                  std::chrono::steady_clock::time_point start, bool show_progress);

  // After the world has reached time `t`. in_funnel() counts what is still in the funnel (asked while it
  // discharges); energies() gives {kinetic, potential} in J (asked while the heap settles). open_gate: the
  // caller opens the outlet and steps on; settled: the heap is ready to measure; failed: reason() says why.
  template <typename InFunnel, typename Energies>
  Next check(double t, const InFunnel& in_funnel, const Energies& energies);

  // The whole run: step() advances the world by run.check_every_s and returns its time; escaped() is "" while
  // the state is sane, else why not; open_gate() opens the outlet. Sets result.ok and result.reason, and
  // result.specimen_info["kinetic_over_potential"] once settled; ends the progress line.
  template <typename Step, typename Escaped, typename OpenGate, typename InFunnel, typename Energies>
  void run(TestResult& result, const Step& step, const Escaped& escaped, const OpenGate& open_gate,
           const InFunnel& in_funnel, const Energies& energies);

  void finish_progress();
  const std::string& reason() const { return reason_; }
  double flow_time_s() const { return flow_time_s_; }               // -1 until the funnel has discharged
  double kinetic_over_potential() const { return settled_ratio_; }  // once settled

 private:
  enum class Stage { fill, discharge, settle };
  Next after_fill(double t);
  Next after_count(double t, std::size_t in_funnel);
  bool settled(double kinetic_j, double potential_j);
  Next overtime(double kinetic_j, double potential_j);
  Next fail(std::string why);

  FunnelRun run_;
  std::size_t total_, left_behind_, remaining_;
  FunnelWords words_;
  RunWatch watch_;
  Stage stage_ = Stage::fill;
  double opened_at_s_ = 0, last_drop_at_s_ = 0, flow_time_s_ = -1, settled_ratio_ = 0;
  std::string reason_;
};

template <typename InFunnel, typename Energies>
FunnelDischarge::Next FunnelDischarge::check(double t, const InFunnel& in_funnel, const Energies& energies) {
  if (!watch_.carry_on(t)) return fail(watch_.timeout_reason());
  Next next = Next::step_on;
  if (stage_ == Stage::fill) {
    next = after_fill(t);
  } else if (stage_ == Stage::discharge) {
    next = after_count(t, in_funnel());
    if (next == Next::failed) return next;
  } else {
    const auto [kinetic_j, potential_j] = energies();
    if (settled(kinetic_j, potential_j)) return Next::settled;
  }
  if (t >= run_.max_time_s) {
    if (stage_ != Stage::settle) return overtime(0, 0);
    const auto [kinetic_j, potential_j] = energies();
    return overtime(kinetic_j, potential_j);
  }
  return next;
}

template <typename Step, typename Escaped, typename OpenGate, typename InFunnel, typename Energies>
void FunnelDischarge::run(TestResult& result, const Step& step, const Escaped& escaped, const OpenGate& open_gate,
                          const InFunnel& in_funnel, const Energies& energies) {
  result.ok = true;
  for (;;) {
    const double t = step();
    const std::string bad = escaped();
    if (!bad.empty()) {
      result.ok = false;
      result.reason = bad;
      break;
    }
    const Next next = check(t, in_funnel, energies);
    if (next == Next::open_gate) {
      open_gate();
    } else if (next == Next::settled) {
      result.specimen_info["kinetic_over_potential"] = kinetic_over_potential();
      break;
    } else if (next == Next::failed) {
      result.ok = false;
      result.reason = reason();
      break;
    }
  }
  finish_progress();
}

}  // namespace demcal::dem
