#pragma once
// Where a threaded run cuts its pairs between threads. Equal parts suit
// equal cores; on a machine whose cores run at different speeds (a shared
// virtual machine, a core busy with interrupts or another program) the
// slowest thread sets each step's time while the others wait at the
// barrier. The cuts follow the threads' measured speeds instead. Results do
// not depend on the cuts (each disk sums its pairs in pair order,
// world_threads.cpp), so moving them by wall-clock timings changes no bit.
#include <cstddef>
#include <vector>

namespace demcal::dem {

// cuts: team + 1 increasing fractions from 0 to 1 (thread t takes the part
// [cuts[t], cuts[t + 1]) of every model's pairs); busy_s: each thread's time
// in its part over the same window of steps. When the slowest thread took
// more than 3 % longer than the fastest, moves each part halfway towards the
// width at which the threads' measured rates would finish together (half
// steps, so one window's noise does not swing the cuts) and returns true.
// No part falls below a quarter of an equal share. Returns false, cuts
// unchanged, when the times are that close or a time is not positive.
bool rebalance_cuts(std::vector<double>& cuts, const std::vector<double>& busy_s);

// team + 1 equal cuts.
std::vector<double> equal_cuts(std::size_t team);

}  // namespace demcal::dem
