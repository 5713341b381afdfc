#pragma once
// What every bonded model does alike: a bonded pair is never skipped, and a
// bond that fails is logged (time, contact point, mode, groups) and loses its
// flag. Each model clears its own bond state.
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/linear_law.hpp"

namespace demcal::dem {

// Skip rule for bonded models: a pair apart is skipped (and forgets its
// shear) only when no bond holds it.
inline bool skip_unbonded_apart(const PairBlock& c, std::size_t k, double gap) {
  return !(c.flags[k] & kBonded) && skip_apart(c, k, gap);
}

// Logs the break of the block's pair k and clears its bonded flag.
inline void break_bond(const PairBlock& c, std::size_t k, const Geometry& g, const Bodies& b, const StepContext& step,
                       BreakMode mode) {
  if (step.breaks)
    step.breaks->push_back({step.time_s, g.cx, g.cy, mode, b.group[static_cast<std::size_t>(c.i[k])],
                            b.group[static_cast<std::size_t>(c.j[k])]});
  c.flags[k] &= ~static_cast<PairFlags>(kBonded);
}

}  // namespace demcal::dem
