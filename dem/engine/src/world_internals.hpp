#pragma once
// What World keeps for its own loops and nothing outside the engine reads:
// the threaded step's bookkeeping (world_threads.cpp) and the neighbour
// search's working arrays (neighbour_list.cpp). Not a public header.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/contacts.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

// A pair the neighbour-list build found: its sort key and its disks' indices.
struct FoundPair {
  std::uint64_t key;
  std::uint32_t i, j;
  bool operator<(const FoundPair& o) const { return key < o.key; }
};

// The threaded force loop's bookkeeping, made at each rebuild (see
// world_threads.cpp). Range t is, for each model position p, the pairs
// [range_start[p * (team + 1) + t], range_start[p * (team + 1) + t + 1]).
struct ThreadPartition {
  std::size_t team = 1;
  std::vector<std::size_t> range_start;
  std::vector<std::uint8_t> direct;             // per disk pair: kAddToI, kAddToJ where that disk is not shared
  std::vector<PairResult> results;              // per disk pair
  std::vector<std::uint32_t> shared;            // disks with pairs in more than one range
  std::vector<std::uint32_t> incidence_start;   // shared disk s's entries are [start[s], start[s + 1])
  std::vector<std::uint32_t> incidence;         // pair index * 2, + 1 where the disk is the pair's j
  std::vector<std::vector<BreakEvent>> log;     // per (model position p, range t) at p * team + t, in pair order
  std::vector<double> cuts;                     // range t: the fractions [cuts[t], cuts[t + 1]) of each block
  struct alignas(64) Busy {                     // a cache line per thread: no false sharing
    double s = 0;
  };
  std::vector<Busy> busy;                       // per thread: time in its ranges since the cuts last moved
  std::uint32_t window_steps = 0;
};

// The neighbour-list build's working arrays, kept from one build to the
// next so a rebuild allocates (and the kernel zeroes) nothing new once the
// list has reached its size (neighbour_list.cpp).
struct ListScratch {
  std::vector<std::uint32_t> cell_of, cell_start, order, bucket_start, bucket_next;
  std::vector<double> x, y, radius;
  std::vector<std::int32_t> clump;
  std::vector<std::vector<FoundPair>> found_by_thread;
  std::vector<FoundPair> found;
  // Per search thread: {1, group, group} of a pair no model is assigned to
  // (reported after the threads, which must not throw), or all 0.
  std::vector<std::array<std::uint8_t, 3>> unassigned;
  ContactSet pairs, wall_pairs;  // the next build's sets: the last but one's storage
};

struct World::Internals {
  ThreadPartition partition;
  std::vector<double> busy_s;  // the threads' times handed to rebalance_cuts
  ListScratch list_scratch;
};

}  // namespace demcal::dem
