#pragma once
// A 2D DEM model and its time stepping: disks, walls, contact models per pair
// of material groups, a cell-grid neighbour list with a skin, explicit central
// differences with local non-viscous damping.
#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "demcal/dem/bodies.hpp"
#include "demcal/dem/clump.hpp"
#include "demcal/dem/contact_geometry.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/contacts.hpp"
#include "demcal/dem/external_forces.hpp"
#include "demcal/dem/walls.hpp"

namespace demcal {
class Rng;
}

namespace demcal::dem {

struct WorldSettings {
  double thickness_m = 1.0;      // disk thickness t (2D, PFC's unit thickness)
  double damping = 0.7;          // local damping alpha: F_d = -alpha |F| sign(v), per component
  double safety_factor = 0.8;    // time step = safety * critical step
  // Neighbour-list skin; 0: 0.25 x the mean radius at the first build, or
  // twice the largest gap a model's pairs pull across (JKR) when that is more
  // at any build. A skin set here that does not exceed that gap is an error.
  double skin_m = 0.0;
  double gravity_x_m_s2 = 0.0, gravity_y_m_s2 = 0.0;
  double fixed_dt_s = 0.0;       // > 0 replaces the computed time step
  // Density scaling for quasi-static tests: > 0 raises each disk's mass and
  // inertia (never lowers them) until the time step is this value. Changes
  // the dynamics, so results must be checked against an unscaled run.
  double density_scaling_dt_s = 0.0;
  // Threads one run's force and integration loops may use (OpenMP): 0 takes
  // OpenMP's current default (omp_set_num_threads, OMP_NUM_THREADS, or every
  // core). Results do not depend on it: the per-disk sums are made in the
  // serial loop's order.
  int threads = 0;
  // A run uses at most one thread per this many disks: below it the cost of
  // starting the threads each step outweighs the work they share (measured on
  // a 2-core machine, docs/benchmarks.md: 2 threads took 1.07x the time of one
  // at 590 disks, 0.84x at 973, 0.67x at 2,366, whole process).
  std::size_t min_disks_per_thread = 500;
  // Every this many steps a threaded run moves the cuts between its threads'
  // parts towards the threads' measured speeds (thread_balance.hpp); 0 keeps
  // the parts where they are (equal, or as set_thread_cuts put them).
  // Results do not depend on it.
  std::uint32_t thread_balance_every_steps = 256;
};


class World {
 public:
  static constexpr std::uint8_t kNoModel = 255;

  explicit World(WorldSettings settings = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  Bodies bodies;
  std::vector<Wall> walls;
  // A box's wall by its role (walls.hpp); throws an Error when the world has no such wall.
  Wall& wall(BoxWall role);
  const Wall& wall(BoxWall role) const;

  // Makes the disks `members` one rigid clump with the given mass, inertia
  // about its centre of mass and centre (x, y); returns its index. Their own
  // masses stop mattering; pairs inside the clump are dropped.
  std::size_t add_clump(const std::vector<std::size_t>& members, double mass_kg, double inertia_kg_m2, double x_m,
                        double y_m);
  const std::vector<Clump>& clumps() const { return clumps_; }
  std::vector<Clump>& clumps() { return clumps_; }

  // Takes a model and returns its index; assign() binds it to a pair of
  // material groups (order does not matter; walls have groups too).
  std::uint8_t add_model(std::unique_ptr<ContactModel> model);
  void assign(std::uint8_t group_a, std::uint8_t group_b, std::uint8_t model_index);
  const ContactModel& model(std::uint8_t index) const { return *models_[index]; }

  // Adds forces from outside the contacts (a boundary's), applied every step
  // from now on in the order added; the world owns them.
  template <typename T>
  T& add_external_forces(std::unique_ptr<T> forces) {
    T& held = *forces;
    external_forces_.push_back(std::move(forces));
    return held;
  }
  // The force and moment each disk gets from the walls now (what the wall
  // contacts give at the current positions), without advancing anything:
  // the static load a boundary takes over when its wall is removed. Pairs of
  // `wall` only, or of every active wall when it is npos.
  void wall_forces_on_disks(std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& moment,
                            std::size_t wall = static_cast<std::size_t>(-1));

  // A checkpoint of the world's state (world_state.cpp): the disks (positions,
  // velocities, forces, properties, groups, ids), the walls, the disk and wall
  // pairs with their models' state, the break log, the time and the steps.
  // Not the models, the settings or external forces: a world built the same
  // way (the same disks, walls and models, bound to the same values) takes it
  // back with read_state (which rebuilds the neighbour list from the restored
  // pairs) and steps on with the same bits the saved one would have after a
  // refresh(). A world with clumps is refused. read_state
  // throws an Error when the file is not one of these or belongs to a world of
  // other disks or models.
  void write_state(std::ostream& out) const;
  void read_state(std::istream& in);

  // Advances one time step (rebuilding the neighbour list when a body has
  // moved more than half the skin since the last build).
  void step();
  void run(std::uint64_t steps);
  // Rebuilds the neighbour list now (after bodies were moved or added by hand).
  void refresh();
  // Material genesis: makes every overlapping disk pair force-free at its
  // overlap (PFC's "remove overlap only"), so the packing carries no
  // locked-in force whatever stiffness the test gives it, then bonds every
  // disk pair whose gap is at most `tolerance_m` and whose model has a bond.
  // With `locked_in_fraction` f > 0 each overlapping pair keeps f of its
  // overlap as force instead (a locked-in stress that the bonds then hold). Each bond draws its random strengths from a
  // generator keyed by `seed` and the ids of its two disks, so a bond's
  // strength does not depend on the order of the disks or of the pairs.
  // Returns the number of bonds installed.
  std::size_t install_bonds(double tolerance_m, std::uint64_t seed,
                            double locked_in_fraction = 0.0);
  // Makes every disk-wall contact force-free as it lies: each overlapping
  // pair's reference overlap becomes its overlap, so walls placed where the
  // packing's vessel was touch every disk that touched the vessel without
  // pushing it (PFC: the vessel's walls become the platens). Returns the
  // number of disk-wall contacts so set.
  std::size_t make_wall_contacts_force_free();
  // Sum of the normal (translational) stiffness of the disks touching wall
  // `w` now, N/m: what a stress servo on that wall pushes against, so its
  // gain can close a set share of the stress error per step without
  // overshooting (PFC's servo rule).
  double wall_contact_stiffness_n_m(std::size_t w) const;
  // Clears the break log and the step and time counters, and stops every
  // body: what came before (relaxing a locked-in stress) prepared the
  // specimen and is not part of the test.
  void start_test();

  double time_s() const { return time_s_; }
  std::uint64_t steps_done() const { return steps_; }
  double dt_s() const { return dt_s_; }
  std::uint64_t rebuilds() const { return rebuilds_; }
  // The neighbour-list skin (settings, or 0.25 x the mean radius), set at the first build, m.
  double skin_m() const { return skin_m_; }
  // Threads the force and integration loops use now (settings, disk count).
  int threads_in_use() const { return threads_in_use_; }
  // Where the threads' parts of the pairs (and of the disks) begin and end,
  // as fractions (thread_balance.hpp); empty before a threaded build.
  // set_thread_cuts takes team + 1 increasing fractions from 0 to 1; they
  // apply at once on a team of that size, else from the build that makes
  // one (with thread_balance_every_steps 0 they then stay).
  const std::vector<double>& thread_cuts() const;
  void set_thread_cuts(std::vector<double> cuts);
  const WorldSettings& settings() const { return settings_; }
  WorldSettings& settings() { return settings_; }

  const ContactSet& pairs() const { return pairs_; }
  ContactSet& pairs() { return pairs_; }
  const ContactSet& wall_pairs() const { return wall_pairs_; }
  // State column `column` (a name the pair's model declares) of disk pair k.
  double pair_state(std::size_t k, const std::string& column) const;
  const std::vector<BreakEvent>& breaks() const { return breaks_; }

  // Kinetic energy (translational + rotational) from the current velocities, J.
  double kinetic_energy() const;
  // Pairs whose disks touch now.
  std::size_t touching_pairs() const;
  // The largest ContactModel::max_bond_utilisation over the models that
  // report one (how close the most loaded bond is to breaking); NaN when no
  // model with disk pairs reports one.
  double max_bond_utilisation() const;

 private:
  void rebuild();
  // The largest gap any model's pairs pull across at the present radii, m.
  double attachment_gap_m() const;
  void build_disk_pairs(ContactSet& fresh);
  void build_wall_pairs(ContactSet& fresh);
  void merge_into(ContactSet& fresh, ContactSet& old, bool walls);
  void update_time_step();
  void refresh_inverse_masses();
  // One step's forces and integration on one thread (world.cpp) or several (world_threads.cpp), same bits.
  void compute_forces();
  void compute_wall_forces();
  void integrate();
  void step_in_threads();
  void build_thread_partition();
  void move_walls();
  // The bodies' rolling limits (type A rolling resistance) from this step's
  // contacts, when a model adds them (serial, in pair order).
  void add_rolling_limits();
  void integrate_clumps(double& max_move2);
  std::uint8_t model_for(std::uint8_t a, std::uint8_t b) const;
  // The mass disk i moves with: its clump's, its own, or 0 when it is fixed.
  double moving_mass(std::size_t i) const;

  WorldSettings settings_;
  std::vector<std::unique_ptr<ContactModel>> models_;
  std::array<std::array<std::uint8_t, 256>, 256> table_;
  ContactSet pairs_, wall_pairs_;
  std::vector<std::size_t> layout_;                      // state columns per model
  std::vector<std::vector<std::string>> column_names_;    // their names per model
  std::vector<std::uint8_t> run_models_, wall_run_models_;  // models with pairs, in pair order
  std::vector<BreakEvent> breaks_;
  std::vector<Clump> clumps_;
  std::vector<std::unique_ptr<ExternalForces>> external_forces_;
  // Positions at the last rebuild, for the skin criterion.
  std::vector<double> x_built_, y_built_;
  std::vector<std::array<double, 2>> wall_built_;
  // 1 / mass and 1 / inertia per disk, refreshed with the time step (at
  // every rebuild, so masses set by hand count from the next refresh(), as
  // genesis's new radii do), so the integration does not divide.
  std::vector<double> inverse_mass_, inverse_inertia_;
  // Per disk, the largest rolling-resistance couple its contacts give it this
  // step (N m); empty while no model adds rolling limits.
  std::vector<double> rolling_limit_;
  bool rolling_limits_ = false;
  // The threaded step's bookkeeping and the neighbour search's working
  // arrays (world_internals.hpp, not a public header: nothing a model or a
  // lab test uses).
  struct Internals;
  std::unique_ptr<Internals> internals_;
  int threads_in_use_ = 1;
  double max_disk_move2_ = 0;
  double skin_m_ = 0;
  double dt_s_ = 0;
  double time_s_ = 0;
  std::uint64_t steps_ = 0;
  std::uint64_t rebuilds_ = 0;
  bool built_ = false;
};

// The disks' indices in the order of their ids, and the clumps' in the order
// of their first members' ids: sums over bodies run in these orders, so their
// bits do not depend on the order the bodies are stored in.
std::vector<std::size_t> disks_by_id(const Bodies& bodies);
std::vector<std::size_t> clumps_by_id(const World& world);

}  // namespace demcal::dem
