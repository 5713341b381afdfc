#pragma once
// Contact models of the 3D engine behind one interface and a registry by
// name, as the 2D engine's: a model computes the forces of its whole block of
// pairs in one call and owns the per-pair state it declares (the contact set
// of demcal/dem/contacts.hpp, shared with 2D). Unlike 2D, a model writes each
// pair's force and moments into PairForces and the world sums them per sphere
// in pair order, so any split of the pairs between threads gives the same bits.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/contacts.hpp"
#include "demcal/dem/model_registry.hpp"
#include "demcal/dem3d/spheres.hpp"
#include "demcal/dem3d/walls.hpp"

namespace demcal {
class Rng;
}

namespace demcal::dem3d {

using dem::ConstPairBlock;
using dem::PairBlock;

// What a bonded model marks on a pair whose bond (or part of it: a flat
// joint's elements) broke this step, with mark_break; a model clears kBonded
// itself when nothing of the bond is left. The world logs the breaks in pair
// order after the step's forces, so the log is the same on any number of
// threads, tension breaks before shear ones, and clears the marks.
constexpr dem::PairFlags kBrokeThisStep = 1u << 8;
constexpr unsigned kTensionBreaksShift = 12, kShearBreaksShift = 18;  // 6-bit counts
constexpr dem::PairFlags kBreakCountMask = 0x3f;
constexpr dem::PairFlags kBreakMarks =
    kBrokeThisStep | (kBreakCountMask << kTensionBreaksShift) | (kBreakCountMask << kShearBreaksShift);

inline dem::PairFlags mark_break(dem::PairFlags flags, bool tension) {
  const unsigned shift = tension ? kTensionBreaksShift : kShearBreaksShift;
  const dem::PairFlags count = std::min<dem::PairFlags>(((flags >> shift) & kBreakCountMask) + 1, kBreakCountMask);
  return (flags & ~(kBreakCountMask << shift)) | kBrokeThisStep | (count << shift);
}
inline unsigned tension_breaks(dem::PairFlags flags) { return (flags >> kTensionBreaksShift) & kBreakCountMask; }
inline unsigned shear_breaks(dem::PairFlags flags) { return (flags >> kShearBreaksShift) & kBreakCountMask; }

struct StepContext {
  double dt_s = 0;
  double time_s = 0;
  // The spheres' records this step (sphere_records.hpp), for a vectorised
  // law; nullptr when a caller (a test) gives none.
  const double* records = nullptr;
};

// Where a block's sphere pair k puts what it gives: the force on sphere i
// (its partner gets the opposite) and the moments about each centre.
//   - Stored per pair (several threads): i's moment at 2k, j's at 2k + 1, and
//     the world sums each sphere's pairs afterwards, in pair order.
//   - Added at once to the spheres' sums (`direct`, one thread: the pairs come
//     in pair order, so each sphere's sum is the same, bit for bit); the force
//     is stored per pair too (the equilibrium measure reads it).
// For a sphere-wall pair, i is the sphere and the wall gets the opposite force;
// wall pairs are always stored.
struct PairForces {
  double *fx, *fy, *fz;
  double *mx, *my, *mz;  // two per pair
  // Direct: the spheres' sums and the block's pair ends (nullptr when stored);
  // sphere a's sums at a * sum_stride (the world keeps a sphere's six sums in
  // one cache line: a pair's scatter then touches two lines, not twelve).
  double *sum_fx = nullptr, *sum_fy = nullptr, *sum_fz = nullptr, *sum_mx = nullptr, *sum_my = nullptr,
         *sum_mz = nullptr;
  std::size_t sum_stride = 1;
  const std::int32_t *i = nullptr, *j = nullptr;

  // The same from pair `first` on (a block's, or a thread's part of it).
  PairForces from(std::size_t first) const {
    PairForces out = *this;
    out.fx = fx + first, out.fy = fy + first, out.fz = fz + first;
    if (sum_fx)
      out.i = i + first, out.j = j + first;
    else
      out.mx = mx + 2 * first, out.my = my + 2 * first, out.mz = mz + 2 * first;
    return out;
  }
  void set(std::size_t k, Vec3 force, Vec3 moment_i, Vec3 moment_j) const {
    fx[k] = force.x, fy[k] = force.y, fz[k] = force.z;
    if (sum_fx) {
      const std::size_t a = static_cast<std::size_t>(i[k]) * sum_stride, b = static_cast<std::size_t>(j[k]) * sum_stride;
      sum_fx[a] += force.x, sum_fy[a] += force.y, sum_fz[a] += force.z;
      sum_mx[a] += moment_i.x, sum_my[a] += moment_i.y, sum_mz[a] += moment_i.z;
      sum_fx[b] -= force.x, sum_fy[b] -= force.y, sum_fz[b] -= force.z;
      sum_mx[b] += moment_j.x, sum_my[b] += moment_j.y, sum_mz[b] += moment_j.z;
      return;
    }
    mx[2 * k] = moment_i.x, my[2 * k] = moment_i.y, mz[2 * k] = moment_i.z;
    mx[2 * k + 1] = moment_j.x, my[2 * k + 1] = moment_j.y, mz[2 * k + 1] = moment_j.z;
  }
};

// The contact geometry of sphere-wall pairs at this step, computed by the
// world from each wall's shape, so models never see the shapes.
struct WallGeometry {
  const double *nx, *ny, *nz;  // unit normal from the sphere towards the wall
  const double* overlap_m;     // > 0 in contact
  const double *vx, *vy, *vz;  // the wall's velocity at the contact point
  WallGeometry from(std::size_t first) const {
    return {nx + first, ny + first, nz + first, overlap_m + first, vx + first, vy + first, vz + first};
  }
};

// The two sides of a pair when it enters the neighbour list.
struct PairInfo {
  double radius_i = 0, radius_j = 0;  // radius_j = 0 for a wall
  std::uint8_t group_i = 0, group_j = 0;
  bool wall = false;
  double mass_i_kg = 0, mass_j_kg = 0;  // 0 for a side that does not move
  double overlap_m = 0;  // the overlap now (negative: a gap); set when a bond is installed
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::string name() const = 0;
  // The state kept per pair, one name per column with its unit in the name.
  virtual std::vector<std::string> state_columns() const = 0;
  // Sets the constants of the block's pair k when it enters the list.
  virtual void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const = 0;
  // Material genesis: the block's pair k carries no force at `overlap_m`
  // (PFC's "remove overlap only"; less than the whole overlap keeps a
  // locked-in share). A model without a reference overlap ignores it.
  virtual void make_force_free(PairBlock& c, std::size_t k, double overlap_m) const {
    (void)c, (void)k, (void)overlap_m;
  }
  // Installs a bond on the block's sphere pair k, drawing its strengths from
  // `rng` (keyed by the pair's ids); false for a model without bonds.
  virtual bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, Rng& rng) const {
    (void)c, (void)k, (void)pair, (void)rng;
    return false;
  }
  // Whether the model's pairs can hold bonds (kBonded: kept in the list
  // however far apart, their breaks logged).
  virtual bool has_bonds() const { return false; }
  // How close the block's most loaded intact bond is to breaking (what the
  // break test compares over the strength, at the last step's state); 0 when
  // none is intact, NaN for a model without bonds.
  virtual double max_bond_utilisation(const ConstPairBlock& c, const Spheres& s) const {
    (void)c, (void)s;
    return std::nan("");
  }
  // The forces of a block of sphere pairs (c.i, c.j sphere indices), into `out` (block-local indices).
  virtual void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const = 0;
  // The forces of a block of sphere-wall pairs (c.j a wall index), from their geometry `g` (block-local).
  virtual void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                           const StepContext& step) const = 0;
  // Translational and rotational stiffness the block's pair k adds to a
  // sphere whose contact lies `arm_m` from its centre (for the time step).
  virtual void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                         double& rotational_nm_rad) const = 0;
  // The stiffer spring of a contact of two spheres of radius r, for a sphere
  // that has no neighbour yet (time step bound).
  virtual double stiffness_estimate(double radius_m) const = 0;
  // The largest damping ratio its dashpots give any mode (0 without dashpots):
  // the step shrinks by sqrt(1 + zeta^2) - zeta, as in 2D.
  virtual double max_damping_ratio() const { return 0.0; }
  // True when the model's forces depend on the masses it was given in
  // PairInfo (a damping set for a restitution): density scaling is then refused.
  virtual bool depends_on_masses() const { return false; }
  // The largest gap across which a pair of spheres no larger than
  // `radius_max_m` stays in contact (an adhesive model's); the neighbour
  // list's skin must exceed it, which the world checks.
  virtual double attachment_gap_m(double radius_max_m) const {
    (void)radius_max_m;
    return 0.0;
  }
  // Rolling resistance of type A: each touching pair of the block adds to
  // `limit_nm` (per sphere) the couple it can give each of its spheres against
  // that sphere's own spin; the world applies the sums as Coulomb friction in
  // rotation. `walls`: a block of sphere-wall pairs (only c.i is a sphere).
  virtual bool adds_rolling_limits() const { return false; }
  virtual void add_rolling_limits(const ConstPairBlock& c, const Spheres& s, bool walls, double* limit_nm) const {
    (void)c, (void)s, (void)walls, (void)limit_nm;
  }
};

// The 3D models by name (a model of the same name in 2D is another law with
// its own keys: each engine has its own registry, model_registry.hpp).
class ContactModelRegistry : public dem::ModelRegistry<ContactModel> {
 public:
  ContactModelRegistry() : dem::ModelRegistry<ContactModel>("3D contact model", "known in 3D") {}
  // Holds the built-in 3D models; defined by the 3D models library.
  static ContactModelRegistry& instance();
};

}  // namespace demcal::dem3d
