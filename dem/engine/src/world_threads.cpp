// The World's threaded step (forces, then the disks' integration, in one
// parallel region), with the serial step's bits.
//
// Each model's block of disk pairs is cut into one part per thread (equal
// pair counts, whole batches); thread t takes part t of every block, so its
// pairs cover one region of the specimen (pairs are sorted by model, then by
// their disks, numbered along a Hilbert curve). A disk whose pairs all lie in
// one thread's parts gets its additions from that thread alone, in pair
// order, as in the serial loop; the thread adds them directly. A disk whose
// pairs lie with several threads (a shared disk: few, where the regions
// meet) gets nothing in the first phase: its pairs' contributions are
// stored, and in the second phase it sums them in pair order with the serial
// loop's signs. Every sum thus gets the same terms in the same order whatever
// the number of threads, and wherever the parts are cut. The break logs,
// joined model by model and part by part, are in pair order.
//
// The parts start equal; every thread_balance_every_steps steps the cuts move
// towards the threads' measured speeds (thread_balance.hpp), so a slower core
// gets fewer pairs and disks.
#include <algorithm>
#include <stdexcept>

#include <omp.h>

#include "demcal/dem/pair_batch.hpp"
#include "demcal/dem/thread_balance.hpp"
#include "demcal/dem/world.hpp"
#include "disk_integration.hpp"
#include "world_internals.hpp"

namespace demcal::dem {

namespace {
// Where fraction cuts[t] of `count` items falls (the last cut at `count`).
std::size_t cut_index(std::size_t count, const std::vector<double>& cuts, std::size_t t) {
  if (t + 1 >= cuts.size()) return count;
  return std::min(count, static_cast<std::size_t>(static_cast<double>(count) * cuts[t]));
}
}  // namespace

void World::set_thread_cuts(std::vector<double> cuts) {
  bool increasing = cuts.size() >= 3 && cuts.front() == 0.0 && cuts.back() == 1.0;
  for (std::size_t t = 1; t < cuts.size() && increasing; ++t) increasing = cuts[t] > cuts[t - 1];
  if (!increasing) throw std::invalid_argument("set_thread_cuts: team + 1 increasing fractions from 0 to 1 expected");
  internals_->partition.cuts = std::move(cuts);
  if (built_ && static_cast<std::size_t>(threads_in_use_) + 1 == internals_->partition.cuts.size()) build_thread_partition();
}

void World::build_thread_partition() {
  ThreadPartition& tp = internals_->partition;
  const std::size_t n = bodies.size(), pairs = pairs_.size();
  const std::size_t team = static_cast<std::size_t>(threads_in_use_);
  // Each model's block cut into `team` parts at the same fractions (equal at
  // first); range t is part t of every block, so a range covers one region of
  // the specimen whatever the models (pairs are sorted by model, then by their
  // disks).
  const std::size_t models = run_models_.size();
  if (tp.cuts.size() != team + 1) tp.cuts = equal_cuts(team);
  if (tp.busy.size() != team) {
    tp.busy.assign(team, {});
    tp.window_steps = 0;
  }
  tp.team = team;
  tp.range_start.resize(models * (team + 1));
  for (std::size_t p = 0; p < models; ++p) {
    const std::size_t begin = pairs_.begin(run_models_[p]), size = pairs_.end(run_models_[p]) - begin;
    for (std::size_t t = 0; t <= team; ++t) tp.range_start[p * (team + 1) + t] = begin + cut_index(size, tp.cuts, t);
  }

  // A disk is shared when its pairs lie in more than one range.
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> range_of(n, kNone);
  std::vector<std::uint8_t> shared(n, 0);
  for (std::size_t p = 0; p < models; ++p)
    for (std::size_t t = 0; t < team; ++t)
      for (std::size_t k = tp.range_start[p * (team + 1) + t]; k < tp.range_start[p * (team + 1) + t + 1]; ++k)
      for (const std::int32_t d : {pairs_.i[k], pairs_.j[k]}) {
        const std::size_t disk = static_cast<std::size_t>(d);
        if (range_of[disk] == kNone) range_of[disk] = static_cast<std::uint32_t>(t);
        shared[disk] |= static_cast<std::uint8_t>(range_of[disk] != t);
      }
  tp.direct.resize(pairs);
  for (std::size_t k = 0; k < pairs; ++k)
    tp.direct[k] = static_cast<std::uint8_t>((shared[static_cast<std::size_t>(pairs_.i[k])] ? 0 : kAddToI) |
                                             (shared[static_cast<std::size_t>(pairs_.j[k])] ? 0 : kAddToJ));

  // Each shared disk's pairs in pair order: a counting sort over the pairs,
  // taken in order.
  std::vector<std::uint32_t> slot(n, kNone);
  tp.shared.clear();
  for (std::size_t d = 0; d < n; ++d)
    if (shared[d]) {
      slot[d] = static_cast<std::uint32_t>(tp.shared.size());
      tp.shared.push_back(static_cast<std::uint32_t>(d));
    }
  tp.incidence_start.assign(tp.shared.size() + 1, 0);
  for (std::size_t k = 0; k < pairs; ++k)
    for (const std::int32_t d : {pairs_.i[k], pairs_.j[k]})
      if (slot[static_cast<std::size_t>(d)] != kNone) ++tp.incidence_start[slot[static_cast<std::size_t>(d)] + 1];
  for (std::size_t s = 0; s < tp.shared.size(); ++s) tp.incidence_start[s + 1] += tp.incidence_start[s];
  tp.incidence.resize(tp.incidence_start.back());
  std::vector<std::uint32_t> next(tp.incidence_start.begin(), tp.incidence_start.end() - 1);
  for (std::size_t k = 0; k < pairs; ++k) {
    const std::uint32_t si = slot[static_cast<std::size_t>(pairs_.i[k])];
    const std::uint32_t sj = slot[static_cast<std::size_t>(pairs_.j[k])];
    if (si != kNone) tp.incidence[next[si]++] = static_cast<std::uint32_t>(2 * k);
    if (sj != kNone) tp.incidence[next[sj]++] = static_cast<std::uint32_t>(2 * k + 1);
  }
  tp.results.resize(pairs);
  tp.log.resize(models * team);
}

void World::step_in_threads() {
  ThreadPartition& tp = internals_->partition;
  const std::size_t n = bodies.size();
  const std::size_t team = tp.team, models = run_models_.size();
  double* __restrict fx = bodies.fx.data();
  double* __restrict fy = bodies.fy.data();
  double* __restrict moment = bodies.moment.data();
  for (Wall& wall : walls) wall.fx = wall.fy = 0;
  DiskArrays arrays = disk_arrays(bodies, inverse_mass_, inverse_inertia_, x_built_, y_built_);
  if (rolling_limits_) rolling_limit_.resize(n);  // sized (add_rolling_limits fills it) before the threads take its address
  arrays.rolling_limit = rolling_limits_ ? rolling_limit_.data() : nullptr;
  const double dt = dt_s_, alpha = settings_.damping;
  const double gx = settings_.gravity_x_m_s2, gy = settings_.gravity_y_m_s2;
  double max_move2 = max_disk_move2_;

  // max is exact, so the threads' maxima combine to the serial value.
#pragma omp parallel num_threads(threads_in_use_) reduction(max : max_move2)
  {
    // A smaller team than asked takes every size-th range each.
    const std::size_t size = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t me = static_cast<std::size_t>(omp_get_thread_num());
    // This thread's disks: the same fractions as its pairs (a smaller team
    // than asked: equal parts).
    const bool whole_team = size == team;
    const std::size_t my_first = whole_team ? cut_index(n, tp.cuts, me) : n * me / size;
    const std::size_t my_last = whole_team ? cut_index(n, tp.cuts, me + 1) : n * (me + 1) / size;
    // 0. The sums start from zero, as the serial loop's cleared sums.
    std::fill(fx + my_first, fx + my_last, 0.0);
    std::fill(fy + my_first, fy + my_last, 0.0);
    std::fill(moment + my_first, moment + my_last, 0.0);
#pragma omp barrier
    // 1. This thread's ranges, model by model: every contribution stored, and
    // added directly to the disks that are not shared. Timed for the cuts.
    const double started_s = omp_get_wtime();
    for (std::size_t t = me; t < team; t += size) {
      for (std::size_t p = 0; p < models; ++p) {
        const std::uint8_t m = run_models_[p];
        std::vector<BreakEvent>& log = tp.log[p * team + t];
        log.clear();
        const std::size_t begin = tp.range_start[p * (team + 1) + t], end = tp.range_start[p * (team + 1) + t + 1];
        if (begin >= end) continue;
        StepContext context{dt_s_, time_s_, settings_.thickness_m, &log, tp.results.data() + begin,
                            tp.direct.data() + begin};
        PairBlock run = pairs_.block(m).slice(begin - pairs_.begin(m), end - pairs_.begin(m));
        models_[m]->disk_forces(run, bodies, context);
      }
    }
    if (whole_team) tp.busy[me].s += omp_get_wtime() - started_s;
#pragma omp barrier
    // 2. The shared disks, each summing its pairs in pair order (x - y is
    // x + (-y) to the bit, so the side only selects a term).
    const std::size_t shared = tp.shared.size();
    for (std::size_t s = shared * me / size; s < shared * (me + 1) / size; ++s) {
      double sum_x = 0.0, sum_y = 0.0, sum_moment = 0.0;
      for (std::uint32_t e = tp.incidence_start[s]; e < tp.incidence_start[s + 1]; ++e) {
        const std::uint32_t entry = tp.incidence[e];
        const PairResult& r = tp.results[entry >> 1];
        const bool is_j = (entry & 1u) != 0;
        sum_x += select(is_j, r.fx, -r.fx);
        sum_y += select(is_j, r.fy, -r.fy);
        sum_moment += select(is_j, r.moment_j, r.moment_i);
      }
      const std::size_t d = tp.shared[s];
      fx[d] = sum_x;
      fy[d] = sum_y;
      moment[d] = sum_moment;
    }
#pragma omp barrier
    // 3. What the serial step does next, on one thread: the breaks in pair
    // order (the ranges follow one another), the wall contacts (few) and
    // the external forces. The end of `single` waits for it.
#pragma omp single
    {
      for (std::size_t p = 0; p < models; ++p)
        for (std::size_t t = 0; t < team; ++t)
          breaks_.insert(breaks_.end(), tp.log[p * team + t].begin(), tp.log[p * team + t].end());
      compute_wall_forces();
      for (auto& forces : external_forces_) forces->add(bodies, time_s_, dt_s_);
      add_rolling_limits();
    }
    // 4. This thread's disks move.
    max_move2 = integrate_disks(arrays, my_first, my_last, dt, alpha, gx, gy, max_move2);
  }
  integrate_clumps(max_move2);
  max_disk_move2_ = max_move2;

  // The cuts follow the threads' speeds over the last window (a smaller team
  // than asked leaves times at 0, and the cuts where they are).
  const std::uint32_t every = settings_.thread_balance_every_steps;
  if (every > 0 && ++tp.window_steps >= every) {
    internals_->busy_s.resize(team);
    for (std::size_t t = 0; t < team; ++t) internals_->busy_s[t] = tp.busy[t].s;
    if (rebalance_cuts(tp.cuts, internals_->busy_s)) build_thread_partition();
    for (auto& b : tp.busy) b.s = 0;
    tp.window_steps = 0;
  }
}

}  // namespace demcal::dem
