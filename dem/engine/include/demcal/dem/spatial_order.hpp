#pragma once
// Orders points along a Hilbert curve, so that disks close in space are
// close in memory: the pair loop then finds a disk's neighbours in the cache
// lines it has just read (LAMMPS re-sorts its atoms in space for the same
// reason). Used where disks get their numbers: genesis places and numbers the
// disks in this order, so a specimen's ids, and with them the pair list's
// order, follow space.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace demcal::dem {

// Index along a Hilbert curve of order 16 of cell (cx, cy), each in [0, 65535].
std::uint64_t hilbert_index(std::uint32_t cx, std::uint32_t cy);

// The permutation that visits (x[k], y[k]) in Hilbert order over their
// bounding box: order[0] is the first point. Ties keep the input order, so
// the result depends only on the points.
std::vector<std::size_t> hilbert_order(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace demcal::dem
