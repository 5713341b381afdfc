#include "demcal/dem/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <omp.h>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "disk_integration.hpp"
#include "world_internals.hpp"

namespace demcal::dem {

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

const std::vector<double>& World::thread_cuts() const { return internals_->partition.cuts; }

World::World(WorldSettings settings) : settings_(settings), internals_(std::make_unique<Internals>()) {
  for (auto& row : table_) row.fill(kNoModel);
  if (!(settings_.thickness_m > 0)) throw Error("thickness must be positive");
  if (settings_.damping < 0 || settings_.damping >= 1) throw Error("local damping must lie in [0, 1)");
  if (!(settings_.safety_factor > 0) || settings_.safety_factor > 1)
    throw Error("time-step safety factor must lie in (0, 1]");
  // Scaled masses are inertial only; gravity would act on them too.
  if (settings_.density_scaling_dt_s > 0 && (settings_.gravity_x_m_s2 != 0 || settings_.gravity_y_m_s2 != 0))
    throw Error("density scaling and gravity cannot be combined (gravity would act on the scaled masses)");
}

Wall& World::wall(BoxWall role) {
  return const_cast<Wall&>(static_cast<const World&>(*this).wall(role));
}

const Wall& World::wall(BoxWall role) const {
  static const char* const kNames[] = {"bottom", "top", "left", "right"};
  if (role >= walls.size())
    throw Error(std::string("the world has no ") + kNames[role] + " wall (" + std::to_string(walls.size()) + " walls)");
  return walls[role];
}

std::uint8_t World::add_model(std::unique_ptr<ContactModel> model) {
  if (models_.size() >= kNoModel) throw Error("too many contact models (at most 254)");
  const std::vector<std::string> columns = model->state_columns();
  if (columns.size() > kMaxStateColumns)
    throw Error("contact model " + model->name() + " declares " + std::to_string(columns.size()) +
                " state columns (at most " + std::to_string(kMaxStateColumns) + ")");
  layout_.push_back(columns.size());
  column_names_.push_back(columns);
  rolling_limits_ = rolling_limits_ || model->adds_rolling_limits();
  models_.push_back(std::move(model));
  built_ = false;
  return static_cast<std::uint8_t>(models_.size() - 1);
}

void World::assign(std::uint8_t group_a, std::uint8_t group_b, std::uint8_t model_index) {
  if (model_index >= models_.size()) throw Error("assign: no contact model with index " + std::to_string(model_index));
  table_[group_a][group_b] = model_index;
  table_[group_b][group_a] = model_index;
  built_ = false;
}

void World::refresh() { rebuild(); }

std::size_t World::add_clump(const std::vector<std::size_t>& members, double mass_kg, double inertia_kg_m2, double x_m,
                             double y_m) {
  if (members.empty()) throw Error("a clump needs at least one disk");
  if (!(mass_kg > 0) || !(inertia_kg_m2 > 0)) throw Error("a clump needs a positive mass and inertia");
  Clump clump;
  clump.x = x_m;
  clump.y = y_m;
  clump.mass = mass_kg;
  clump.inertia = inertia_kg_m2;
  const std::int32_t id = static_cast<std::int32_t>(clumps_.size());
  for (std::size_t i : members) {
    if (i >= bodies.size()) throw Error("clump member " + std::to_string(i) + " is not a disk");
    if (bodies.clump[i] >= 0) throw Error("disk " + std::to_string(i) + " already belongs to a clump");
    bodies.clump[i] = id;
    bodies.vx[i] = bodies.vy[i] = bodies.w[i] = 0;
    clump.members.push_back(i);
    clump.offset_x.push_back(bodies.x[i] - x_m);
    clump.offset_y.push_back(bodies.y[i] - y_m);
  }
  clumps_.push_back(std::move(clump));
  built_ = false;
  return clumps_.size() - 1;
}

std::size_t World::install_bonds(double tolerance_m, std::uint64_t seed, double locked_in_fraction) {
  if (!(locked_in_fraction >= 0 && locked_in_fraction <= 1))
    throw Error("install_bonds: the locked-in fraction must lie in [0, 1]");
  rebuild();
  std::size_t installed = 0;
  for (std::uint8_t m : run_models_) {
    PairBlock block = pairs_.block(m);
    for (std::size_t k = 0; k < block.size; ++k) {
      const std::size_t i = static_cast<std::size_t>(block.i[k]), j = static_cast<std::size_t>(block.j[k]);
      // The overlap as the force loop computes it, so a force-free pair is exactly force-free.
      const double dx = bodies.x[j] - bodies.x[i], dy = bodies.y[j] - bodies.y[i];
      const double gap = -disk_overlap_m(bodies.radius[i], bodies.radius[j], centre_distance_m(dx, dy));
      if (gap < 0) models_[m]->make_force_free(block, k, -gap * (1 - locked_in_fraction));
      if (gap > tolerance_m) continue;
      PairInfo info{bodies.radius[i], bodies.radius[j], bodies.group[i], bodies.group[j], false, -gap};
      const std::uint32_t a = bodies.id[i], b = bodies.id[j];
      Rng rng(keyed_seed(seed, std::min(a, b), std::max(a, b)), 0x626f6e64 /* "bond" */);
      installed += models_[m]->install_bond(block, k, info, settings_.thickness_m, rng) ? 1 : 0;
    }
  }
  update_time_step();  // bonds stiffen the disks
  return installed;
}

std::size_t World::make_wall_contacts_force_free() {
  rebuild();
  std::size_t touching = 0;
  for (std::uint8_t m : wall_run_models_) {
    PairBlock block = wall_pairs_.block(m);
    for (std::size_t k = 0; k < block.size; ++k) {
      const std::size_t i = static_cast<std::size_t>(block.i[k]);
      const Wall& wall = walls[static_cast<std::size_t>(block.j[k])];
      if (!wall.active) continue;
      // The overlap as the force loop computes it, so the contact is exactly force-free.
      double dx, dy, distance;
      wall_offset(wall, bodies.x[i], bodies.y[i], dx, dy, distance);
      const double overlap = wall_overlap_m(bodies.radius[i], distance);
      if (overlap <= 0) continue;
      models_[m]->make_force_free(block, k, overlap);
      ++touching;
    }
  }
  return touching;
}

double World::wall_contact_stiffness_n_m(std::size_t w) const {
  double sum = 0;
  if (w >= walls.size() || !walls[w].active) return 0;
  for (std::uint8_t m : wall_run_models_) {
    const ConstPairBlock block = wall_pairs_.block(m);
    for (std::size_t k = 0; k < block.size; ++k) {
      if (static_cast<std::size_t>(block.j[k]) != w) continue;
      const std::size_t i = static_cast<std::size_t>(block.i[k]);
      double dx, dy, distance;
      wall_offset(walls[w], bodies.x[i], bodies.y[i], dx, dy, distance);
      if (wall_overlap_m(bodies.radius[i], distance) <= 0) continue;
      double translational = 0, rotational = 0;
      models_[m]->stiffness(block, k, bodies.radius[i], translational, rotational);
      sum += translational;
    }
  }
  return sum;
}

void World::start_test() {
  breaks_.clear();
  steps_ = 0;
  time_s_ = 0;
  std::fill(bodies.vx.begin(), bodies.vx.end(), 0.0);
  std::fill(bodies.vy.begin(), bodies.vy.end(), 0.0);
  std::fill(bodies.w.begin(), bodies.w.end(), 0.0);
  for (Clump& clump : clumps_) clump.vx = clump.vy = clump.w = 0;
}

double World::pair_state(std::size_t k, const std::string& column) const {
  if (k >= pairs_.size()) throw Error("pair_state: no pair " + std::to_string(k));
  const std::vector<std::string>& names = column_names_[pairs_.model[k]];
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == column) return pairs_.state(k, c);
  throw Error("contact model " + models_[pairs_.model[k]]->name() + " keeps no state column \"" + column + "\"");
}

double World::moving_mass(std::size_t i) const {
  if (bodies.fixed[i]) return 0.0;
  const std::int32_t clump = bodies.clump[i];
  return clump >= 0 ? clumps_[static_cast<std::size_t>(clump)].mass : bodies.mass[i];
}

void World::refresh_inverse_masses() {
  const std::size_t n = bodies.size();
  inverse_mass_.resize(n);
  inverse_inertia_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    inverse_mass_[i] = 1.0 / bodies.mass[i];
    inverse_inertia_[i] = 1.0 / bodies.inertia[i];
  }
}

void World::update_time_step() {
  if (settings_.fixed_dt_s > 0) {
    dt_s_ = settings_.fixed_dt_s;
    refresh_inverse_masses();
    return;
  }
  const std::size_t n = bodies.size();
  std::vector<double> kt(n, 0.0), kr(n, 0.0);
  auto add = [&](const ContactSet& set, const std::vector<std::uint8_t>& models, bool wall) {
    for (std::uint8_t m : models) {
      const ConstPairBlock c = set.block(m);
      for (std::size_t k = 0; k < c.size; ++k) {
        const std::size_t i = static_cast<std::size_t>(c.i[k]);
        double t = 0, r = 0;
        models_[m]->stiffness(c, k, bodies.radius[i], t, r);
        kt[i] += t;
        kr[i] += r;
        if (!wall) {
          const std::size_t j = static_cast<std::size_t>(c.j[k]);
          models_[m]->stiffness(c, k, bodies.radius[j], t, r);
          kt[j] += t;
          kr[j] += r;
        }
      }
    }
  };
  add(pairs_, run_models_, false);
  add(wall_pairs_, wall_run_models_, true);
  double dt = std::numeric_limits<double>::infinity();
  std::array<std::vector<std::uint8_t>, 256> group_models;  // filled on first need, per material group
  // Critical step each disk must reach under density scaling.
  const double scaled_step = settings_.density_scaling_dt_s / settings_.safety_factor;
  if (scaled_step > 0)
    for (const auto& m : models_)
      if (m->depends_on_masses())
        throw Error("density scaling would change the masses contact model " + m->name() +
                    " set its damping from (its coefficient of restitution); run it without density scaling");
  for (std::size_t i = 0; i < n; ++i) {
    if (bodies.fixed[i]) continue;
    if (kt[i] <= 0) {
      // No neighbour yet: bound the step by one contact of the stiffest model the disk's group can meet (a soft
      // rockfill disk alone in the air must not take the step a bonded bedrock pair needs).
      std::vector<std::uint8_t>& can_meet = group_models[bodies.group[i]];
      if (can_meet.empty())
        for (std::size_t g = 0; g < table_.size(); ++g) {
          const std::uint8_t m = table_[bodies.group[i]][g];
          if (m != kNoModel && std::find(can_meet.begin(), can_meet.end(), m) == can_meet.end()) can_meet.push_back(m);
        }
      for (std::uint8_t m : can_meet)
        kt[i] = std::max(kt[i], models_[m]->stiffness_estimate(bodies.radius[i], settings_.thickness_m));
      kr[i] = kt[i] * bodies.radius[i] * bodies.radius[i];
    }
    if (scaled_step > 0) {
      bodies.mass[i] = std::max(bodies.mass[i], kt[i] * scaled_step * scaled_step);
      bodies.inertia[i] = std::max(bodies.inertia[i], kr[i] * scaled_step * scaled_step);
    }
    if (bodies.clump[i] >= 0) continue;  // bounded through its clump below
    if (kt[i] > 0) dt = std::min(dt, std::sqrt(bodies.mass[i] / kt[i]));
    if (kr[i] > 0) dt = std::min(dt, std::sqrt(bodies.inertia[i] / kr[i]));
  }
  // A clump: the stiffness of all its disks' contacts, rotational stiffness
  // about its centre of mass. It moves with its own mass and inertia (its
  // members' are never used), so density scaling raises those.
  for (Clump& c : clumps_) {
    double ct = 0, cr = 0;
    for (std::size_t k = 0; k < c.members.size(); ++k) {
      const std::size_t i = c.members[k];
      ct += kt[i];
      cr += kr[i] + kt[i] * (c.offset_x[k] * c.offset_x[k] + c.offset_y[k] * c.offset_y[k]);
    }
    if (scaled_step > 0) {
      c.mass = std::max(c.mass, ct * scaled_step * scaled_step);
      c.inertia = std::max(c.inertia, cr * scaled_step * scaled_step);
    }
    if (ct > 0) dt = std::min(dt, std::sqrt(c.mass / ct));
    if (cr > 0) dt = std::min(dt, std::sqrt(c.inertia / cr));
  }
  if (!std::isfinite(dt) || dt <= 0) throw Error("cannot find a stable time step (no stiffness or no mass)");
  // Dashpots shorten the stable step (a model without them leaves it as it is: the factor is exactly 1).
  double zeta = 0;
  for (const auto& m : models_) zeta = std::max(zeta, m->max_damping_ratio());
  dt_s_ = settings_.safety_factor * dt * (std::sqrt(1.0 + zeta * zeta) - zeta);
  refresh_inverse_masses();
}

void World::compute_forces() {
  bodies.clear_forces();
  for (Wall& wall : walls) wall.fx = wall.fy = 0;
  StepContext context{dt_s_, time_s_, settings_.thickness_m, &breaks_};
  for (std::uint8_t m : run_models_) {
    PairBlock block = pairs_.block(m);
    models_[m]->disk_forces(block, bodies, context);
  }
  compute_wall_forces();
}

void World::compute_wall_forces() {
  StepContext context{dt_s_, time_s_, settings_.thickness_m, &breaks_};
  for (std::uint8_t m : wall_run_models_) {
    PairBlock block = wall_pairs_.block(m);
    models_[m]->wall_forces(block, bodies, walls, context);
  }
}

void World::wall_forces_on_disks(std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& moment,
                                 std::size_t wall) {
  if (!built_ || inverse_mass_.size() != bodies.size()) rebuild();
  // The wall models on a copy of their pairs, the walls and the disks' sums:
  // shear springs advance and walls collect forces when a model runs, and
  // none of that may happen outside a step.
  ContactSet pairs = wall_pairs_;
  std::vector<Wall> walls_copy = walls;
  if (wall != static_cast<std::size_t>(-1))
    for (std::size_t w = 0; w < walls_copy.size(); ++w) walls_copy[w].active = walls_copy[w].active && w == wall;
  std::vector<BreakEvent> breaks;
  const std::vector<double> keep_fx = bodies.fx, keep_fy = bodies.fy, keep_moment = bodies.moment;
  std::fill(bodies.fx.begin(), bodies.fx.end(), 0.0);
  std::fill(bodies.fy.begin(), bodies.fy.end(), 0.0);
  std::fill(bodies.moment.begin(), bodies.moment.end(), 0.0);
  // A zero step: the models see no relative motion, so shear springs keep their value.
  StepContext context{0.0, time_s_, settings_.thickness_m, &breaks};
  for (std::uint8_t m : wall_run_models_) {
    PairBlock block = pairs.block(m);
    models_[m]->wall_forces(block, bodies, walls_copy, context);
  }
  fx = bodies.fx;
  fy = bodies.fy;
  moment = bodies.moment;
  bodies.fx = keep_fx;
  bodies.fy = keep_fy;
  bodies.moment = keep_moment;
}

void World::add_rolling_limits() {
  if (!rolling_limits_) return;
  rolling_limit_.assign(bodies.size(), 0.0);
  const ContactSet &pairs = pairs_, &wall_pairs = wall_pairs_;
  for (std::uint8_t m : run_models_) models_[m]->add_rolling_limits(pairs.block(m), bodies, false, rolling_limit_.data());
  for (std::uint8_t m : wall_run_models_)
    models_[m]->add_rolling_limits(wall_pairs.block(m), bodies, true, rolling_limit_.data());
}

void World::integrate() {
  const std::size_t n = bodies.size();
  DiskArrays arrays = disk_arrays(bodies, inverse_mass_, inverse_inertia_, x_built_, y_built_);
  arrays.rolling_limit = rolling_limits_ ? rolling_limit_.data() : nullptr;
  const double dt = dt_s_, alpha = settings_.damping;
  const double gx = settings_.gravity_x_m_s2, gy = settings_.gravity_y_m_s2;
  double max_move2 = integrate_disks(arrays, 0, n, dt, alpha, gx, gy, max_disk_move2_);
  integrate_clumps(max_move2);
  max_disk_move2_ = max_move2;
}

void World::integrate_clumps(double& max_move2) {
  const double dt = dt_s_, alpha = settings_.damping;
  auto sign = [](double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); };
  // Clumps own disjoint sets of disks, so threads may share them out; the
  // max is exact in any order, so the result is the serial one.
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(clumps_.size());
  double largest_move2 = max_move2;
#pragma omp parallel for num_threads(threads_in_use_) schedule(static) reduction(max : largest_move2) \
    if (threads_in_use_ > 1 && count > 1)
  for (std::ptrdiff_t index = 0; index < count; ++index) {
    Clump& c = clumps_[static_cast<std::size_t>(index)];
    // Resultant force and moment about the centre of mass.
    double fx = c.mass * settings_.gravity_x_m_s2, fy = c.mass * settings_.gravity_y_m_s2, mz = 0, limit = 0;
    for (std::size_t k = 0; k < c.members.size(); ++k) {
      const std::size_t i = c.members[k];
      fx += bodies.fx[i];
      fy += bodies.fy[i];
      mz += bodies.moment[i] + c.offset_x[k] * bodies.fy[i] - c.offset_y[k] * bodies.fx[i];
      if (rolling_limits_) limit += rolling_limit_[i];
    }
    c.vx += (fx - alpha * std::abs(fx) * sign(c.vx)) / c.mass * dt;
    c.vy += (fy - alpha * std::abs(fy) * sign(c.vy)) / c.mass * dt;
    c.w += (mz - alpha * std::abs(mz) * sign(c.w)) / c.inertia * dt;
    if (rolling_limits_) c.w = rolling_friction_spin(c.w, limit * dt / c.inertia);
    c.x += c.vx * dt;
    c.y += c.vy * dt;
    // Rotate the member offsets exactly, so the clump keeps its shape.
    const double cs = std::cos(c.w * dt), sn = std::sin(c.w * dt);
    for (std::size_t k = 0; k < c.members.size(); ++k) {
      const double ox = cs * c.offset_x[k] - sn * c.offset_y[k];
      const double oy = sn * c.offset_x[k] + cs * c.offset_y[k];
      c.offset_x[k] = ox;
      c.offset_y[k] = oy;
      const std::size_t i = c.members[k];
      bodies.x[i] = c.x + ox;
      bodies.y[i] = c.y + oy;
      bodies.vx[i] = c.vx - c.w * oy;
      bodies.vy[i] = c.vy + c.w * ox;
      bodies.w[i] = c.w;
      const double ddx = bodies.x[i] - x_built_[i], ddy = bodies.y[i] - y_built_[i];
      largest_move2 = std::max(largest_move2, ddx * ddx + ddy * ddy);
    }
  }
  max_move2 = largest_move2;
}

void World::move_walls() {
  for (Wall& wall : walls) {
    if (!wall.active) continue;
    if (wall.servo) {
      // Stress the disks exert on the wall along its inward normal.
      const double loaded = wall.servo_length_m * settings_.thickness_m;
      const double stress = -(wall.fx * wall.inward_nx + wall.fy * wall.inward_ny) / loaded;
      double speed = wall.servo_gain_m_s_per_pa * (wall.servo_target_stress_pa - stress);
      speed = std::clamp(speed, -wall.servo_max_speed_m_s, wall.servo_max_speed_m_s);
      wall.vx = speed * wall.inward_nx;
      wall.vy = speed * wall.inward_ny;
    }
    wall.advance(dt_s_);
  }
}

void World::step() {
  // Disks added by hand since the last build: rebuild (their masses too).
  if (!built_ || inverse_mass_.size() != bodies.size()) rebuild();
  // Rebuild once some disk may have closed the skin with a neighbour or a wall.
  double disk_move = std::sqrt(max_disk_move2_);
  double wall_move = 0;
  for (std::size_t w = 0; w < walls.size() && w < wall_built_.size(); ++w)
    wall_move = std::max(wall_move, std::hypot(walls[w].x0 - wall_built_[w][0], walls[w].y0 - wall_built_[w][1]));
  if (2.0 * disk_move > skin_m_ || disk_move + wall_move > skin_m_ || wall_built_.size() != walls.size()) rebuild();
  if (threads_in_use_ > 1) {
    step_in_threads();
  } else {
    compute_forces();
    for (auto& forces : external_forces_) forces->add(bodies, time_s_, dt_s_);
    add_rolling_limits();
    integrate();
  }
  for (auto& forces : external_forces_) forces->after_integration(bodies, time_s_, dt_s_);
  move_walls();
  time_s_ += dt_s_;
  ++steps_;
}

void World::run(std::uint64_t steps) {
  for (std::uint64_t s = 0; s < steps; ++s) step();
}

std::vector<std::size_t> disks_by_id(const Bodies& bodies) {
  std::vector<std::size_t> order(bodies.size());
  std::iota(order.begin(), order.end(), 0);
  // Every world built today stores its disks in id order: then no sort (the equilibrium checks call this often).
  if (!std::is_sorted(bodies.id.begin(), bodies.id.end()))
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return bodies.id[i] < bodies.id[j]; });
  return order;
}

std::vector<std::size_t> clumps_by_id(const World& world) {
  const std::vector<Clump>& clumps = world.clumps();
  std::vector<std::uint32_t> first(clumps.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::size_t c = 0; c < clumps.size(); ++c)
    for (std::size_t i : clumps[c].members) first[c] = std::min(first[c], world.bodies.id[i]);
  std::vector<std::size_t> order(clumps.size());
  std::iota(order.begin(), order.end(), 0);
  if (!std::is_sorted(first.begin(), first.end()))
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return first[a] < first[b]; });
  return order;
}

double World::kinetic_energy() const {
  // Clumps, then free disks, each in the order of their ids (a clump's: its
  // first member's), so the bits do not depend on how the disks are stored.
  double energy = 0;
  for (std::size_t c : clumps_by_id(*this)) {
    const Clump& k = clumps_[c];
    energy += 0.5 * k.mass * (k.vx * k.vx + k.vy * k.vy) + 0.5 * k.inertia * k.w * k.w;
  }
  for (std::size_t i : disks_by_id(bodies))
    if (bodies.clump[i] < 0)
      energy += 0.5 * bodies.mass[i] * (bodies.vx[i] * bodies.vx[i] + bodies.vy[i] * bodies.vy[i]) +
                0.5 * bodies.inertia[i] * bodies.w[i] * bodies.w[i];
  return energy;
}

double World::max_bond_utilisation() const {
  double most = NAN;
  for (std::size_t m = 0; m < models_.size(); ++m) {
    const auto index = static_cast<std::uint8_t>(m);
    if (pairs_.begin(index) == pairs_.end(index)) continue;
    const double u = models_[m]->max_bond_utilisation(pairs_.block(index), bodies);
    if (!std::isnan(u)) most = std::isnan(most) ? u : std::max(most, u);
  }
  return most;
}

std::size_t World::touching_pairs() const {
  std::size_t count = 0;
  for (PairFlags f : pairs_.flags) count += (f & kTouching) != 0;
  return count;
}

}  // namespace demcal::dem
