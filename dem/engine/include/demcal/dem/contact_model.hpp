#pragma once
// Contact models behind one interface and a registry by name, in the manner
// of LAMMPS pair styles: a new model is one file in dem/models/src plus one
// line in dem/models/src/builtin_models.cpp. The world assigns a model to
// each pair of material groups (mortar-mortar, mortar-aggregate, disk-wall ...).
//
// A model computes the forces of its whole block of pairs in one call, so the
// virtual call happens once per model and step, not once per contact, and it
// owns the per-pair state it declares (see contacts.hpp).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/bodies.hpp"
#include "demcal/dem/contacts.hpp"
#include "demcal/dem/model_registry.hpp"
#include "demcal/dem/walls.hpp"

namespace demcal {
class Rng;
}

namespace demcal::dem {

struct PairResult;

struct StepContext {
  double dt_s = 0;
  double time_s = 0;
  double thickness_m = 1;
  std::vector<BreakEvent>* breaks = nullptr;  // where bond breaks are logged
  // Set when several threads share a block: each disk pair's contribution is
  // stored here (index = the block's pair index) for the world to sum, instead
  // of being added to the disks (see for_disk_pairs).
  PairResult* pair_results = nullptr;
  // With pair_results, the pairs whose disks one thread alone sums: bit
  // kAddToI (kAddToJ) of direct[k] adds pair k's contribution to its i (j),
  // in pair order (index as pair_results), and pair_results[k] is written
  // only when a disk is left out.
  const std::uint8_t* direct = nullptr;
};

// The two sides of a pair when it enters the neighbour list.
struct PairInfo {
  double radius_i = 0, radius_j = 0;  // radius_j = 0 for a wall
  std::uint8_t group_i = 0, group_j = 0;
  bool wall = false;
  double overlap = 0;  // current overlap (negative: a gap), set when a bond is installed
  // The mass each side moves with (a clump's for its member disks), kg; 0 for
  // a side that does not move (a wall, a fixed disk). Set when a pair enters
  // the neighbour list; models with a viscous damping take it from here.
  double mass_i_kg = 0, mass_j_kg = 0;
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::string name() const = 0;

  // The state the model keeps per pair, one name per column with its unit in
  // the name ("kn_n_m", "shear_force_n"); the contact set stores these
  // columns for this model's pairs only and carries them across neighbour-list
  // rebuilds. Column c is PairBlock::column[c].
  virtual std::vector<std::string> state_columns() const = 0;

  // Sets the constants of the block's pair k (stiffness, friction) when it enters the list.
  virtual void initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m) const = 0;
  // Material genesis, before bonds are installed: the block's overlapping
  // pair k carries no force at `overlap_m` (its reference overlap; PFC's
  // "remove overlap only" sets the reference gap to the gap). The world passes
  // the pair's whole overlap, or less of it to keep a locked-in share. A model
  // without a reference ignores it.
  virtual void make_force_free(PairBlock& c, std::size_t k, double overlap_m) const;
  // Installs a bond on the block's pair k (material genesis); false when the model has none.
  virtual bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m, Rng& rng) const;

  // Adds the forces of a block of disk pairs to the bodies.
  virtual void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const = 0;
  // Adds the forces of a block of disk-wall pairs to the disks and walls.
  virtual void wall_forces(PairBlock& c, Bodies& b, std::vector<Wall>& walls, const StepContext& step) const = 0;

  // Translational and rotational stiffness the block's pair k adds to a disk
  // whose contact lies `arm_m` from its centre (for the critical time step).
  virtual void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                         double& rotational_nm_rad) const = 0;
  // Normal force the block's pair k carries at `overlap_m` (for the
  // equilibrium measure of material genesis), N.
  virtual double normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const = 0;
  // How close the block's most loaded intact bond is to breaking: the largest
  // ratio, over its bonded pairs, of what the model's break test compares
  // (a stress or a force) to the bond's strength, at the state of the last
  // step (below 1 for every bond that held). 0 when no bond is intact; NaN
  // for a model that has no bonds or does not report it. A UCS whose platens
  // run faster while the specimen is elastic slows them on it
  // (loading.elastic_speedup).
  virtual double max_bond_utilisation(const ConstPairBlock& c, const Bodies& b) const;
  // The stiffer spring (normal or shear) of a contact between two disks of
  // radius r, for a disk that has no neighbour yet (time step bound).
  virtual double stiffness_estimate(double radius_m, double thickness_m) const = 0;
  // The largest gap (m) across which a pair of disks no larger than
  // `radius_max_m`, or such a disk and a wall, can still carry force: 0 for
  // models that act only in contact, JKR's delta_c for its largest pairs.
  // The neighbour list must keep such pairs, so its skin must exceed it.
  virtual double attachment_gap_m(double /*radius_max_m*/) const { return 0.0; }
  // Rolling resistance on each body's own spin (type A): whether the model
  // adds to the bodies' rolling limits, and the adding, after each step's
  // forces, in the block's pair order: limit_nm[i] grows by the largest
  // couple the pair's contact can give disk i against its rotation (and j's
  // for disk pairs). The integration applies each body's limit as Coulomb
  // friction in rotation, so a body at rest stays at rest while the other
  // moments on it stay below its limit.
  virtual bool adds_rolling_limits() const { return false; }
  virtual void add_rolling_limits(const ConstPairBlock& c, const Bodies& b, bool walls, double* limit_nm) const;
  // The largest damping ratio its dashpots give any mode of a pair it joins
  // (normal, tangential, rolling): a dashpot's coefficient over the critical
  // one for that mode's stiffness and effective mass. The time step shrinks
  // by sqrt(1 + zeta^2) - zeta for it, the central-difference bound of a
  // damped oscillator (Belytschko et al., Nonlinear Finite Elements, 6.6).
  // 0 for a model without dashpots.
  virtual double max_damping_ratio() const { return 0.0; }
  // True when the model's forces depend on the masses it was given in
  // PairInfo (a damping set for a coefficient of restitution): density
  // scaling, which raises masses later, is then refused.
  virtual bool depends_on_masses() const { return false; }
};

// The 2D engine's models by name (model_registry.hpp): a new model is one
// file in dem/models/src and one line in builtin_models.cpp.
class ContactModelRegistry : public ModelRegistry<ContactModel> {
 public:
  ContactModelRegistry() : ModelRegistry<ContactModel>("contact model", "known") {}
  // Holds the built-in models; defined by the models library (dem/models).
  static ContactModelRegistry& instance();
};
using ContactModelFactory = ContactModelRegistry::Factory;

}  // namespace demcal::dem
