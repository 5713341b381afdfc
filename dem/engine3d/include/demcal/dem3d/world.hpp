#pragma once
// A 3D DEM model and its time stepping: spheres, walls (walls.hpp), contact models
// per pair of material groups, a cell-grid neighbour list with a skin,
// explicit central differences with PFC3D's local non-viscous damping.
//
// Reproducible: at every rebuild the world stores the spheres along a Morton
// curve (by their positions, ties by id: an order that depends on the state
// alone, not on how the spheres were added), keeps the pairs in that order,
// computes each pair's force on its own and sums each sphere's pairs in pair
// order; so the bits depend neither on the number of threads nor on the order
// the spheres were given in, and neighbours sit close in memory. A pair's
// orientation (i the smaller id) and its carried state are keyed by ids.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "demcal/dem/contacts.hpp"
#include "demcal/dem3d/clump.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/spheres.hpp"
#include "demcal/dem3d/walls.hpp"

namespace demcal::dem3d {

struct WorldSettings {
  double damping = 0.7;        // local damping alpha: F_d = -alpha |F| sign(v), per component (PFC3D)
  double safety_factor = 0.8;  // time step = safety * critical step
  double skin_m = 0.0;         // neighbour-list skin; 0: 0.25 x the mean radius at the first build
  Vec3 gravity_m_s2;
  double fixed_dt_s = 0.0;  // > 0 replaces the computed time step
  // Density scaling for quasi-static tests: > 0 raises each sphere's (and
  // clump's) mass and inertia, never lowers them, until the time step is this
  // value. It changes the dynamics: results must be checked against an
  // unscaled run. Refused with a model whose damping is set from the masses.
  double density_scaling_dt_s = 0.0;
  // Threads one run's loops may use (OpenMP): 0 takes OpenMP's default.
  // Results do not depend on it.
  int threads = 0;
  // A run uses at most one thread per this many spheres (below it, starting
  // the threads each step costs more than they share).
  std::size_t min_spheres_per_thread = 500;
};

class World {
 public:
  static constexpr std::uint8_t kNoModel = 255;

  explicit World(WorldSettings settings = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  Spheres spheres;
  std::vector<Wall> walls;

  // Makes the spheres `members` (indices now) one rigid clump with the given
  // mass, principal moments of inertia (about its centre of mass), the
  // orientation of its principal axes and its centre; returns its index. The
  // members' own masses stop mattering; pairs inside the clump are dropped.
  // An Error when a member is fixed, already in a clump, or given twice.
  std::size_t add_clump(const std::vector<std::size_t>& members, double mass_kg, Vec3 principal_inertia_kg_m2,
                        Quaternion orientation, Vec3 centre_m);
  const std::vector<Clump>& clumps() const { return clumps_; }
  std::vector<Clump>& clumps() { return clumps_; }

  // Takes a model and returns its index; assign() binds it to a pair of
  // material groups (order does not matter; walls have groups too).
  std::uint8_t add_model(std::unique_ptr<ContactModel> model);
  void assign(std::uint8_t group_a, std::uint8_t group_b, std::uint8_t model_index);
  const ContactModel& model(std::uint8_t index) const { return *models_[index]; }

  // Advances one time step (rebuilding the neighbour list when a sphere or a
  // wall has moved more than half the skin since the last build).
  void step();
  void run(std::uint64_t steps);
  // Rebuilds the neighbour list now (after spheres were moved or added by hand).
  void refresh();

  // Material genesis: makes every overlapping sphere pair force-free at its
  // overlap (PFC's "remove overlap only"), or at (1 - locked_in_fraction) of
  // it to keep a locked-in share, then bonds every pair whose gap is at most
  // `tolerance_m` and whose model has bonds. Each bond draws its strengths
  // from a generator keyed by `seed` and the ids of its two spheres, so a
  // bond's strength depends on neither the order of the spheres nor the
  // threads. A bond keeps its pair in the list however far apart the spheres
  // move. Returns the number of bonds installed.
  std::size_t install_bonds(double tolerance_m, std::uint64_t seed, double locked_in_fraction = 0.0);
  // Makes every touching sphere-wall contact force-free as it lies (walls
  // placed where the vessel was touch the specimen without pushing it).
  // Returns the number of such contacts.
  std::size_t make_wall_contacts_force_free();
  // Clears the break log, the step and time counters and every velocity and
  // spin: what came before prepared the specimen and is not the test.
  void start_test();
  // Every bond break since start_test (or the start), in the order they
  // happened and, within a step, in pair order.
  const std::vector<dem::BreakEvent>& breaks() const { return breaks_; }
  // Intact bonds now.
  std::size_t bonded_pairs() const;
  // The largest ContactModel::max_bond_utilisation over the models with
  // bonds; NaN when no model has bonds.
  double max_bond_utilisation() const;

  double time_s() const { return time_s_; }
  std::uint64_t steps_done() const { return steps_; }
  double dt_s() const { return dt_s_; }
  std::uint64_t rebuilds() const { return rebuilds_; }
  double skin_m() const { return skin_m_; }
  int threads_in_use() const { return threads_in_use_; }
  const WorldSettings& settings() const { return settings_; }
  WorldSettings& settings() { return settings_; }

  const dem::ContactSet& pairs() const { return pairs_; }
  const dem::ContactSet& wall_pairs() const { return wall_pairs_; }
  // State column `column` (a name the pair's model declares) of sphere pair k.
  double pair_state(std::size_t k, const std::string& column) const;
  // The translational stiffness of the contacts touching wall `w` now, N/m:
  // what a stress servo on it pushes against (PFC's rule for its gain).
  double wall_contact_stiffness_n_m(std::size_t w) const;
  // Pairs whose spheres touch now (kTouching set by their model).
  std::size_t touching_pairs() const;
  // PFC's equilibrium measure after a step: the mean unbalanced force over the
  // free spheres (contacts, walls and gravity) over the mean force of the
  // touching pairs; 0 when nothing touches. Summed in storage order (set by
  // the state alone), so a stop on it is the same on any number of threads.
  double force_ratio() const;
  // The force on sphere i from its contacts (spheres and walls) in the last
  // step, N, summed in pair order (gravity and damping not included): what a
  // driven (fixed) sphere's neighbours push it with.
  Vec3 contact_force(std::size_t i) const;
  // Kinetic energy (translational + rotational), summed in id order, J.
  double kinetic_energy() const;
  // Index of the sphere with id `id` now (the world reorders the arrays).
  std::size_t index_of(std::uint32_t id) const;

 private:
  void rebuild();
  void reorder_spheres();
  void build_sphere_pairs(dem::ContactSet& fresh, std::vector<std::uint64_t>& keys);
  void build_wall_pairs(dem::ContactSet& fresh, std::vector<std::uint64_t>& keys);
  void keep_bonded_pairs(std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>>& found) const;
  void move_walls();
  void carry_state(dem::ContactSet& fresh, const std::vector<std::uint64_t>& fresh_keys, const dem::ContactSet& old,
                   const std::vector<std::uint64_t>& old_keys);
  void build_sums();
  void update_time_step();
  void compute_wall_geometry();
  void keep_one_contact_per_mesh_point();
  void compute_pair_forces();
  void log_breaks();
  void integrate();
  void integrate_clumps(double& max_move2);
  std::uint8_t model_for(std::uint8_t a, std::uint8_t b) const;
  // f plus sphere i's pair and wall forces of the last step, in pair order.
  Vec3 add_contact_forces(std::size_t i, Vec3 f) const;

  WorldSettings settings_;
  std::vector<std::unique_ptr<ContactModel>> models_;
  std::array<std::array<std::uint8_t, 256>, 256> table_;
  dem::ContactSet pairs_, wall_pairs_;
  // Each pair's (id_i << 32 | id_j), or (id << 32 | wall) for a wall pair:
  // the key that carries a pair's state across rebuilds and reorderings.
  std::vector<std::uint64_t> pair_keys_, wall_keys_;
  std::vector<std::size_t> layout_;
  std::vector<std::uint8_t> run_models_, wall_run_models_;
  std::vector<Clump> clumps_;
  std::vector<dem::BreakEvent> breaks_;
  struct Internals;  // per-pair force arrays, the per-sphere sums, positions at the last build
  std::unique_ptr<Internals> internals_;
  int threads_in_use_ = 1;
  double skin_m_ = 0;
  double dt_s_ = 0;
  double time_s_ = 0;
  std::uint64_t steps_ = 0;
  std::uint64_t rebuilds_ = 0;
  bool built_ = false;
  bool any_mesh_ = false;  // some wall is a mesh's triangle (set at rebuild)
};

}  // namespace demcal::dem3d
