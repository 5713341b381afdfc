#pragma once
// Pairs that may touch (within the neighbour-list skin) and the state their
// contact model keeps, as contiguous arrays. A pair in the list is not
// necessarily touching: its model decides from the overlap each step.
//
// Disk-disk pairs: j is a disk index. Disk-wall pairs live in a second set
// where j is a wall index.
#include <cstdint>
#include <vector>

namespace demcal::dem {

enum ContactFlags : std::uint8_t {
  kTouching = 1,   // overlapped in the last step
  kBonded = 2,     // an intact bond (contact or parallel)
};

enum class BreakMode : std::uint8_t { Tension = 0, Shear = 1 };

struct BreakEvent {
  double time_s;
  double x_m, y_m;
  BreakMode mode;
  std::uint8_t group_i, group_j;
};

struct ContactSet {
  std::vector<std::int32_t> i, j;
  std::vector<std::uint8_t> model;   // index into the world's model table
  std::vector<std::uint8_t> flags;
  // Linear part
  std::vector<double> kn, ks;        // N/m
  std::vector<double> mu;            // friction coefficient
  std::vector<double> fs;            // shear force along t = (-n_y, n_x), N
  // Bond part (contact bond: strengths as forces; parallel bond: as stresses)
  std::vector<double> bond_kn, bond_ks;    // parallel bond stiffness per area, Pa/m
  std::vector<double> bond_area, bond_inertia, bond_radius;  // m^2, m^4, m
  std::vector<double> bond_fn, bond_fs, bond_m;  // bond force (compression > 0), shear force, moment
  std::vector<double> strength_n, strength_s;    // tensile and shear strength (N or Pa, per model)
  std::vector<double> bond_overlap;              // overlap when the bond was installed (force-free there), m

  std::size_t size() const { return i.size(); }
  void clear();
  // Appends a pair with every state value zero.
  std::size_t add(std::int32_t a, std::int32_t b, std::uint8_t model_index);
  // Copies the state of pair `from` of `other` into pair `to` of this set.
  void copy_state(std::size_t to, const ContactSet& other, std::size_t from);
  void reserve(std::size_t n);
};

}  // namespace demcal::dem
