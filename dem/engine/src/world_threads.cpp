// The World's threaded force loop, with the serial loop's sums to the bit.
//
// Each thread owns the disks of one range of ids (genesis numbers disks
// along a Hilbert curve, so a range is a compact region). Pairs are sorted by
// (model, id_i, id_j), so the pairs whose i a thread owns are one contiguous
// segment of each model's block. A pair whose j another thread owns (a
// crossing pair: few, along the regions' borders) is computed first and its
// contribution stored; then every thread walks its own segments in pair
// order, adding the crossing pairs where it owns j before its segment (their
// i has a lower id, so they come first in pair order), computing the other
// pairs and adding their forces as the serial loop does. Every disk thus gets
// its additions in the serial order, whatever the number of threads, and the
// bond breaks are logged in pair order.
#include <algorithm>

#include <omp.h>

#include "demcal/core/error.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

void World::build_thread_partition() {
  const std::size_t n = bodies.size(), team = static_cast<std::size_t>(threads_in_use_);
  ThreadPartition& tp = partition_;
  // Owner by the rank of the disk's id: equal numbers of disks per thread.
  std::vector<std::uint32_t> ids(bodies.id.begin(), bodies.id.end());
  std::sort(ids.begin(), ids.end());
  std::vector<std::uint32_t> first_id(team);
  for (std::size_t t = 0; t < team; ++t) first_id[t] = ids[n * t / team];
  tp.owner.resize(n);
  for (std::size_t d = 0; d < n; ++d)
    tp.owner[d] = static_cast<std::uint8_t>(
        std::upper_bound(first_id.begin(), first_id.end(), bodies.id[d]) - first_id.begin() - 1);

  const std::size_t models = run_models_.size();
  tp.segment.assign(models * (team + 1), 0);
  tp.crossing.clear();
  tp.crossing_range.assign(models * (team + 1), 0);
  std::vector<std::vector<std::uint32_t>> incoming(models * team);
  for (std::size_t p = 0; p < models; ++p) {
    const std::uint8_t m = run_models_[p];
    const std::size_t begin = pairs_.begin(m), end = pairs_.end(m);
    std::size_t k = begin;
    for (std::size_t t = 0; t < team; ++t) {
      tp.segment[p * (team + 1) + t] = k;
      tp.crossing_range[p * (team + 1) + t] = tp.crossing.size();
      for (; k < end && tp.owner[static_cast<std::size_t>(pairs_.i[k])] == t; ++k) {
        const std::size_t owner_j = tp.owner[static_cast<std::size_t>(pairs_.j[k])];
        if (owner_j == t) continue;
        incoming[p * team + owner_j].push_back(static_cast<std::uint32_t>(tp.crossing.size()));
        tp.crossing.push_back(static_cast<std::uint32_t>(k));
      }
    }
    tp.segment[p * (team + 1) + team] = k;
    tp.crossing_range[p * (team + 1) + team] = tp.crossing.size();
    if (k != end) throw Error("internal: the pairs are not sorted by the owner of their lower-id disk");
  }
  tp.incoming_start.assign(models * team + 1, 0);
  tp.incoming.clear();
  for (std::size_t s = 0; s < models * team; ++s) {
    tp.incoming.insert(tp.incoming.end(), incoming[s].begin(), incoming[s].end());
    tp.incoming_start[s + 1] = tp.incoming.size();
  }
  tp.results.resize(tp.crossing.size());
  tp.crossing_log.resize(team);
  tp.crossing_break.assign(tp.crossing.size(), {});
  tp.log.resize(models * team);
}

void World::compute_disk_forces_in_threads() {
  // Phase 1 clears the force sums itself.
  ThreadPartition& tp = partition_;
  const std::size_t team = static_cast<std::size_t>(threads_in_use_);
  const std::size_t models = run_models_.size();
  double* __restrict fx = bodies.fx.data();
  double* __restrict fy = bodies.fy.data();
  double* __restrict moment = bodies.moment.data();

#pragma omp parallel num_threads(threads_in_use_)
  // Ranges were cut for `team` threads: each thread takes every team-th of
  // them, so a smaller team than asked still covers them all.
  {
    const std::size_t size = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t me = static_cast<std::size_t>(omp_get_thread_num());
    // 1. The disks' force sums start from zero, and the crossing pairs (shared
    // out evenly, whoever owns them) store their contributions and keep any
    // break aside.
    {
      const std::size_t n = bodies.size();
      std::fill(fx + n * me / size, fx + n * (me + 1) / size, 0.0);
      std::fill(fy + n * me / size, fy + n * (me + 1) / size, 0.0);
      std::fill(moment + n * me / size, moment + n * (me + 1) / size, 0.0);
      std::vector<BreakEvent>& log = tp.crossing_log[me];
      log.clear();
      const std::size_t crossing = tp.crossing.size();
      std::size_t p = 0;
      for (std::size_t s = crossing * me / size; s < crossing * (me + 1) / size; ++s) {
        while (s >= tp.crossing_range[p * (team + 1) + team]) ++p;  // the model of crossing pair s
        const std::uint8_t m = run_models_[p];
        const std::size_t k = tp.crossing[s] - pairs_.begin(m);
        const std::size_t logged = log.size();
        StepContext context{dt_s_, time_s_, settings_.thickness_m, &log, &tp.results[s]};
        PairBlock one = pairs_.block(m).slice(k, k + 1);
        models_[m]->disk_forces(one, bodies, context);
        tp.crossing_break[s] = {static_cast<std::uint32_t>(me), static_cast<std::uint32_t>(logged),
                                static_cast<std::uint32_t>(log.size() - logged)};
      }
    }
#pragma omp barrier
    // 2. Each thread its own disks, in pair order.
    for (std::size_t t = me; t < team; t += size) {
      for (std::size_t p = 0; p < models; ++p) {
        const std::uint8_t m = run_models_[p];
        PairBlock block = pairs_.block(m);
        const std::size_t base = pairs_.begin(m);
        std::vector<BreakEvent>& log = tp.log[p * team + t];
        log.clear();
        for (std::size_t a = tp.incoming_start[p * team + t]; a < tp.incoming_start[p * team + t + 1]; ++a) {
          const std::uint32_t s = tp.incoming[a];
          const PairResult& r = tp.results[s];
          const std::size_t j = static_cast<std::size_t>(pairs_.j[tp.crossing[s]]);
          fx[j] += r.fx;
          fy[j] += r.fy;
          moment[j] += r.moment_j;
        }
        StepContext context{dt_s_, time_s_, settings_.thickness_m, &log, nullptr};
        std::size_t from = tp.segment[p * (team + 1) + t] - base;
        const std::size_t to = tp.segment[p * (team + 1) + t + 1] - base;
        for (std::size_t s = tp.crossing_range[p * (team + 1) + t]; s < tp.crossing_range[p * (team + 1) + t + 1];
             ++s) {
          const std::size_t k = tp.crossing[s] - base;
          if (k > from) {
            PairBlock run = block.slice(from, k);
            models_[m]->disk_forces(run, bodies, context);
          }
          const PairResult& r = tp.results[s];
          const std::size_t i = static_cast<std::size_t>(pairs_.i[tp.crossing[s]]);
          fx[i] -= r.fx;
          fy[i] -= r.fy;
          moment[i] += r.moment_i;
          const CrossingBreaks& b = tp.crossing_break[s];
          for (std::uint32_t e = 0; e < b.count; ++e) log.push_back(tp.crossing_log[b.thread][b.first + e]);
          from = k + 1;
        }
        if (to > from) {
          PairBlock run = block.slice(from, to);
          models_[m]->disk_forces(run, bodies, context);
        }
      }
    }
  }

  // Breaks in pair order: model by model, each model's segments in order.
  for (std::size_t p = 0; p < models; ++p)
    for (std::size_t t = 0; t < team; ++t) {
      const auto& log = tp.log[p * team + t];
      breaks_.insert(breaks_.end(), log.begin(), log.end());
    }
}

}  // namespace demcal::dem
