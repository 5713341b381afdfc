#include "demcal/dem3d/world.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <numeric>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/select.hpp"
#include "demcal/dem3d/sphere_records.hpp"
#include "world_internals.hpp"

namespace demcal::dem3d {

World::World(WorldSettings settings) : settings_(settings), internals_(std::make_unique<Internals>()) {
  for (auto& row : table_) row.fill(kNoModel);
}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

std::uint8_t World::add_model(std::unique_ptr<ContactModel> model) {
  if (models_.size() >= kNoModel) throw Error("too many contact models in one world");
  layout_.push_back(model->state_columns().size());
  models_.push_back(std::move(model));
  built_ = false;
  return static_cast<std::uint8_t>(models_.size() - 1);
}

void World::assign(std::uint8_t group_a, std::uint8_t group_b, std::uint8_t model_index) {
  if (model_index >= models_.size()) throw Error("assign: no contact model with that index");
  table_[group_a][group_b] = table_[group_b][group_a] = model_index;
  built_ = false;
}

std::uint8_t World::model_for(std::uint8_t a, std::uint8_t b) const { return table_[a][b]; }

void World::refresh() { rebuild(); }

void World::run(std::uint64_t steps) {
  for (std::uint64_t s = 0; s < steps; ++s) step();
}

void World::rebuild() {
  Internals& in = *internals_;
  const std::size_t n = spheres.size();
  if (skin_m_ <= 0) {
    if (settings_.skin_m > 0) {
      skin_m_ = settings_.skin_m;
    } else {
      // Summed in ascending order: the same bits however the spheres were given.
      std::vector<double> radii = spheres.radius;
      std::sort(radii.begin(), radii.end());
      double sum = 0;
      for (double r : radii) sum += r;
      skin_m_ = n > 0 ? 0.25 * sum / static_cast<double>(n) : 1e-3;
    }
  }
  // A pair still pulling across a gap the skin does not cover would leave the
  // list at this build and lose its force and history.
  double attached = 0;
  {
    double radius_max = 0;
    for (double r : spheres.radius) radius_max = std::max(radius_max, r);
    for (const auto& model : models_) attached = std::max(attached, model->attachment_gap_m(radius_max));
  }
  // The default skin follows the models' need as the spheres grow; one set by hand must already cover it.
  if (settings_.skin_m <= 0) skin_m_ = std::max(skin_m_, 2.0 * attached);
  if (attached > 0 && attached >= skin_m_)
    throw Error("the neighbour-list skin (" + format_double(skin_m_) + " m) does not exceed the largest gap a contact "
                "model's pairs pull across (" + format_double(attached) +
                " m, JKR's delta_c at the largest sphere): raise the skin above it");
  if (n > 0) reorder_spheres();
  // The clumps' members at their new places.
  {
    std::vector<std::size_t> index_by_id;
    for (std::size_t i = 0; i < n; ++i) {
      if (spheres.id[i] >= index_by_id.size()) index_by_id.resize(spheres.id[i] + std::size_t{1}, n);
      index_by_id[spheres.id[i]] = i;
    }
    in.member_index.assign(clumps_.size(), {});
    for (std::size_t k = 0; k < clumps_.size(); ++k)
      for (std::uint32_t id : clumps_[k].member_ids) in.member_index[k].push_back(index_by_id[id]);
    for (auto* v : {&in.member_fx, &in.member_fy, &in.member_fz, &in.member_mx, &in.member_my, &in.member_mz})
      v->assign(clumps_.empty() ? 0 : n, 0.0);
    in.clump_force.assign(clumps_.size(), Vec3{});
  }
  // The new lists go into the storage of the build before last, then change places with the old ones.
  dem::ContactSet &fresh = in.spare_pairs, &fresh_walls = in.spare_wall_pairs;
  std::vector<std::uint64_t> &keys = in.spare_keys, &wall_keys = in.spare_wall_keys;
  fresh.set_layout(layout_);
  fresh_walls.set_layout(layout_);
  build_sphere_pairs(fresh, keys);
  build_wall_pairs(fresh_walls, wall_keys);
  carry_state(fresh, keys, pairs_, pair_keys_);
  carry_state(fresh_walls, wall_keys, wall_pairs_, wall_keys_);
  std::swap(pairs_, fresh);
  std::swap(wall_pairs_, fresh_walls);
  std::swap(pair_keys_, keys);
  std::swap(wall_keys_, wall_keys);
  run_models_.clear();
  wall_run_models_.clear();
  for (std::size_t m = 0; m < models_.size(); ++m) {
    const auto model = static_cast<std::uint8_t>(m);
    if (pairs_.end(model) > pairs_.begin(model)) run_models_.push_back(model);
    if (wall_pairs_.end(model) > wall_pairs_.begin(model)) wall_run_models_.push_back(model);
  }
  in.sphere_pair_forces.resize(pairs_.size());
  in.wall_pair_forces.resize(wall_pairs_.size());
  in.wall_geometry.resize(wall_pairs_.size());
  build_sums();
  in.x_built = spheres.x, in.y_built = spheres.y, in.z_built = spheres.z;
  in.walls_built = walls;
  any_mesh_ = std::any_of(walls.begin(), walls.end(), [](const Wall& w) { return w.mesh >= 0; });
  in.extent_m = 0;
  if (n > 0) {
    Vec3 low = spheres.position(0), high = low;
    for (std::size_t i = 0; i < n; ++i) {
      low = {std::min(low.x, spheres.x[i]), std::min(low.y, spheres.y[i]), std::min(low.z, spheres.z[i])};
      high = {std::max(high.x, spheres.x[i]), std::max(high.y, spheres.y[i]), std::max(high.z, spheres.z[i])};
    }
    in.extent_m = norm(high - low);
  }
  in.max_move2 = 0;
  update_time_step();
  const int wanted = settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
  const std::size_t most = std::max<std::size_t>(1, n / std::max<std::size_t>(1, settings_.min_spheres_per_thread));
  threads_in_use_ = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(1, wanted)), most));
  ++rebuilds_;
  built_ = true;
}

void World::carry_state(dem::ContactSet& fresh, const std::vector<std::uint64_t>& fresh_keys,
                        const dem::ContactSet& old, const std::vector<std::uint64_t>& old_keys) {
  const bool walls_set = &old == &wall_pairs_;
  std::vector<std::uint8_t> carried(fresh.size(), 0);
  if (!walls_set) {
    // Sphere pairs: each model's fresh pairs run by (first, second) storage
    // index, so the pair of two spheres is found in its first sphere's short
    // row; an old pair's spheres are found by id.
    const std::size_t n = spheres.size();
    std::vector<std::uint32_t> index_of_id;
    for (std::size_t i = 0; i < n; ++i) {
      if (spheres.id[i] >= index_of_id.size()) index_of_id.resize(spheres.id[i] + std::size_t{1}, UINT32_MAX);
      if (index_of_id[spheres.id[i]] != UINT32_MAX)
        throw Error("two spheres have the id " + std::to_string(spheres.id[i]) + " (ids order pairs and must be unique)");
      index_of_id[spheres.id[i]] = static_cast<std::uint32_t>(i);
    }
    std::vector<std::uint32_t> row(n + 1);
    for (std::size_t m = 0; m < models_.size(); ++m) {
      const auto model = static_cast<std::uint8_t>(m);
      const std::size_t begin = fresh.begin(model), end = fresh.end(model);
      if (end == begin || old.end(model) == old.begin(model)) continue;
      std::fill(row.begin(), row.end(), 0);
      for (std::size_t k = begin; k < end; ++k) ++row[std::min(fresh.i[k], fresh.j[k]) + std::size_t{1}];
      for (std::size_t i = 0; i < n; ++i) row[i + 1] += row[i];
      for (std::size_t k = old.begin(model); k < old.end(model); ++k) {
        const std::uint64_t key = old_keys[k];
        const std::uint64_t id_i = key >> 32, id_j = key & 0xffffffffu;
        if (id_i >= index_of_id.size() || id_j >= index_of_id.size()) continue;
        const std::uint32_t a = index_of_id[id_i], b = index_of_id[id_j];
        if (a == UINT32_MAX || b == UINT32_MAX) continue;
        const std::uint32_t first = std::min(a, b);
        for (std::size_t f = begin + row[first]; f < begin + row[first + 1]; ++f)
          if (fresh_keys[f] == key) {
            fresh.copy_state(f, old, k);
            carried[f] = 1;
            break;
          }
      }
    }
  } else {
    // Wall pairs (few): each model's pairs, old and fresh, in key order: one walk matches them.
    auto by_key = [](const std::vector<std::uint64_t>& keys, std::size_t begin, std::size_t end) {
      std::vector<std::pair<std::uint64_t, std::size_t>> out;
      out.reserve(end - begin);
      for (std::size_t k = begin; k < end; ++k) out.emplace_back(keys[k], k);
      std::sort(out.begin(), out.end());
      return out;
    };
    for (std::size_t m = 0; m < models_.size(); ++m) {
      const auto model = static_cast<std::uint8_t>(m);
      const auto old_sorted = by_key(old_keys, old.begin(model), old.end(model));
      const auto fresh_sorted = by_key(fresh_keys, fresh.begin(model), fresh.end(model));
      std::size_t from = 0;
      for (const auto& [key, k] : fresh_sorted) {
        while (from < old_sorted.size() && old_sorted[from].first < key) ++from;
        if (from < old_sorted.size() && old_sorted[from].first == key) {
          fresh.copy_state(k, old, old_sorted[from].second);
          carried[k] = 1;
        }
      }
    }
  }
  // The pairs new to the list take their constants from their model.
  for (std::size_t m = 0; m < models_.size(); ++m) {
    const auto model = static_cast<std::uint8_t>(m);
    PairBlock block = fresh.block(model);
    const std::size_t begin = fresh.begin(model);
    for (std::size_t k = begin; k < fresh.end(model); ++k) {
      if (carried[k]) continue;
      const auto i = static_cast<std::size_t>(fresh.i[k]);
      // The mass each side moves with: a clump member moves with its clump's.
      const auto moving_mass = [&](std::size_t s) {
        if (spheres.fixed[s]) return 0.0;
        return spheres.clump[s] >= 0 ? clumps_[static_cast<std::size_t>(spheres.clump[s])].mass_kg : spheres.mass[s];
      };
      PairInfo info;
      info.radius_i = spheres.radius[i];
      info.group_i = spheres.group[i];
      info.mass_i_kg = moving_mass(i);
      if (walls_set) {
        info.wall = true;
        info.group_j = walls[static_cast<std::size_t>(fresh.j[k])].group;
      } else {
        const auto j = static_cast<std::size_t>(fresh.j[k]);
        info.radius_j = spheres.radius[j];
        info.group_j = spheres.group[j];
        info.mass_j_kg = moving_mass(j);
      }
      models_[m]->initialise(block, k - begin, info);
    }
  }
}

void World::build_sums() {
  Internals& in = *internals_;
  const std::size_t n = spheres.size();
  auto fill = [n](std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& entry, std::size_t count,
                  const auto& each) {
    begin.assign(n + 1, 0);
    each([&](std::size_t sphere, std::uint32_t) { ++begin[sphere + 1]; });
    for (std::size_t i = 0; i < n; ++i) begin[i + 1] += begin[i];
    entry.assign(begin[n], 0);
    std::vector<std::uint32_t> next(begin.begin(), begin.end() - 1);
    each([&](std::size_t sphere, std::uint32_t value) { entry[next[sphere]++] = value; });
    (void)count;
  };
  fill(in.sum_begin, in.sum_entry, pairs_.size(), [&](const auto& put) {
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      put(static_cast<std::size_t>(pairs_.i[k]), static_cast<std::uint32_t>(2 * k));
      put(static_cast<std::size_t>(pairs_.j[k]), static_cast<std::uint32_t>(2 * k + 1));
    }
  });
  fill(in.wall_begin, in.wall_entry, wall_pairs_.size(), [&](const auto& put) {
    for (std::size_t k = 0; k < wall_pairs_.size(); ++k)
      put(static_cast<std::size_t>(wall_pairs_.i[k]), static_cast<std::uint32_t>(k));
  });
}

void World::update_time_step() {
  Internals& in = *internals_;
  const std::size_t n = spheres.size();
  in.inverse_mass.resize(n);
  in.inverse_inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    in.inverse_mass[i] = 1.0 / spheres.mass[i];
    in.inverse_inertia[i] = 1.0 / spheres.inertia[i];
  }
  if (settings_.fixed_dt_s > 0) {
    dt_s_ = settings_.fixed_dt_s;
    return;
  }
  std::vector<double> kt(n, 0.0), kr(n, 0.0);
  for (std::uint8_t m : run_models_) {
    const dem::ConstPairBlock c = static_cast<const dem::ContactSet&>(pairs_).block(m);
    for (std::size_t k = 0; k < c.size; ++k) {
      for (const auto end : {static_cast<std::size_t>(c.i[k]), static_cast<std::size_t>(c.j[k])}) {
        double t = 0, r = 0;
        models_[m]->stiffness(c, k, spheres.radius[end], t, r);
        kt[end] += t;
        kr[end] += r;
      }
    }
  }
  for (std::uint8_t m : wall_run_models_) {
    const dem::ConstPairBlock c = static_cast<const dem::ContactSet&>(wall_pairs_).block(m);
    for (std::size_t k = 0; k < c.size; ++k) {
      const auto i = static_cast<std::size_t>(c.i[k]);
      double t = 0, r = 0;
      models_[m]->stiffness(c, k, spheres.radius[i], t, r);
      kt[i] += t;
      kr[i] += r;
    }
  }
  double dt = std::numeric_limits<double>::infinity();
  // The critical step each body must reach under density scaling.
  const double scaled_step = settings_.density_scaling_dt_s / settings_.safety_factor;
  if (scaled_step > 0)
    for (const auto& m : models_)
      if (m->depends_on_masses())
        throw Error("density scaling would change the masses contact model " + m->name() +
                    " set its damping from (its coefficient of restitution); run it without density scaling");
  for (std::size_t i = 0; i < n; ++i) {
    if (spheres.fixed[i]) continue;
    if (kt[i] <= 0) {  // no neighbour yet: one contact of the stiffest model
      for (const auto& m : models_) kt[i] = std::max(kt[i], m->stiffness_estimate(spheres.radius[i]));
      kr[i] = kt[i] * spheres.radius[i] * spheres.radius[i];
    }
    if (spheres.clump[i] >= 0) continue;  // bounded through its clump below
    if (scaled_step > 0) {
      spheres.mass[i] = std::max(spheres.mass[i], kt[i] * scaled_step * scaled_step);
      spheres.inertia[i] = std::max(spheres.inertia[i], kr[i] * scaled_step * scaled_step);
      in.inverse_mass[i] = 1.0 / spheres.mass[i];
      in.inverse_inertia[i] = 1.0 / spheres.inertia[i];
    }
    if (kt[i] > 0) dt = std::min(dt, std::sqrt(spheres.mass[i] / kt[i]));
    if (kr[i] > 0) dt = std::min(dt, std::sqrt(spheres.inertia[i] / kr[i]));
  }
  // A clump: the stiffness of all its members' contacts, the rotational one
  // about its centre, against its own mass and smallest principal moment.
  for (std::size_t k = 0; k < clumps_.size(); ++k) {
    Clump& c = clumps_[k];
    double ct = 0, cr = 0;
    for (std::size_t m = 0; m < in.member_index[k].size(); ++m) {
      const std::size_t i = in.member_index[k][m];
      const Vec3 offset = c.member_offsets_body_m[m];
      ct += kt[i];
      cr += kr[i] + kt[i] * dot(offset, offset);
    }
    if (scaled_step > 0) {
      // The clump's own mass and principal moments (its members' never count).
      c.mass_kg = std::max(c.mass_kg, ct * scaled_step * scaled_step);
      Vec3& moments = c.principal_inertia_kg_m2;
      const double least = cr * scaled_step * scaled_step;
      moments = {std::max(moments.x, least), std::max(moments.y, least), std::max(moments.z, least)};
    }
    const Vec3 inertia = c.principal_inertia_kg_m2;
    if (ct > 0) dt = std::min(dt, std::sqrt(c.mass_kg / ct));
    if (cr > 0) dt = std::min(dt, std::sqrt(std::min({inertia.x, inertia.y, inertia.z}) / cr));
  }
  if (!std::isfinite(dt) || dt <= 0) throw Error("cannot find a stable time step (no stiffness or no mass)");
  double zeta = 0;
  for (const auto& m : models_) zeta = std::max(zeta, m->max_damping_ratio());
  dt_s_ = settings_.safety_factor * dt * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

void World::step() {
  Internals& in = *internals_;
  bool stale = !built_ || in.x_built.size() != spheres.size();
  const double half_skin2 = 0.25 * skin_m_ * skin_m_;
  if (!stale) {
    stale = in.max_move2 > half_skin2 || in.walls_built.size() != walls.size();
    for (std::size_t w = 0; w < walls.size() && !stale; ++w) {
      // A triangle moves as far as its farthest corner; a plane or a cylinder
      // by its point's displacement plus, when it turns, at most its axis's
      // change times the spheres' extent.
      const Wall &now = walls[w], &then = in.walls_built[w];
      if (now.active != then.active || now.group != then.group || now.shape != then.shape) {
        stale = true;  // its pairs are another set now
        break;
      }
      double moved = 0;
      if (now.shape == WallShape::triangle)
        for (int v = 0; v < 3; ++v) moved = std::max(moved, norm(now.vertices[v] - then.vertices[v]));
      else
        moved = norm(now.point_m - then.point_m) + norm(now.axis - then.axis) * in.extent_m +
                std::abs(now.radius_m - then.radius_m);
      stale = moved * moved > half_skin2;
    }
  }
  if (stale) rebuild();
  compute_pair_forces();
  integrate();
  move_walls();
  time_s_ += dt_s_;
  ++steps_;
}

void World::compute_pair_forces() {
  Internals& in = *internals_;
  compute_wall_geometry();
  const int team = threads_in_use_;
  // The spheres' records for the vectorised laws, each thread its share.
  const std::size_t n = spheres.size();
  in.records.resize(kRecordSize * n);
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto parts = static_cast<std::size_t>(omp_get_num_threads());
    pack_sphere_records(spheres, n * t / parts, n * (t + 1) / parts, in.records.data());
  }
  const StepContext step{dt_s_, time_s_, in.records.data()};
  in.direct = team == 1;
  PairForces sphere_out = in.sphere_pair_forces.view();
  const PairForces wall_out = in.wall_pair_forces.view();
  if (in.direct) {
    if (!in.sums_zero || in.sums.size() != kSumStride * n) in.sums.assign(kSumStride * n, 0.0);
    in.sums_zero = false;
    double* sums = in.sums.data();
    sphere_out.sum_fx = sums + kSumFx, sphere_out.sum_fy = sums + kSumFy, sphere_out.sum_fz = sums + kSumFz;
    sphere_out.sum_mx = sums + kSumMx, sphere_out.sum_my = sums + kSumMy, sphere_out.sum_mz = sums + kSumMz;
    sphere_out.sum_stride = kSumStride;
    sphere_out.i = pairs_.i.data(), sphere_out.j = pairs_.j.data();
  }
  const WallGeometry geometry = in.wall_geometry.view();
  // Each thread takes the same share of every model's block: a pair's force
  // depends on its own state alone, so any split gives the same numbers.
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto parts = static_cast<std::size_t>(omp_get_num_threads());
    for (std::uint8_t m : run_models_) {
      PairBlock block = pairs_.block(m);
      const std::size_t lo = block.size * t / parts, hi = block.size * (t + 1) / parts;
      if (hi <= lo) continue;
      PairBlock part = block.slice(lo, hi);
      models_[m]->sphere_forces(part, spheres, sphere_out.from(pairs_.begin(m) + lo), step);
    }
    for (std::uint8_t m : wall_run_models_) {
      PairBlock block = wall_pairs_.block(m);
      const std::size_t lo = block.size * t / parts, hi = block.size * (t + 1) / parts;
      if (hi <= lo) continue;
      PairBlock part = block.slice(lo, hi);
      const std::size_t first = wall_pairs_.begin(m) + lo;
      models_[m]->wall_forces(part, spheres, geometry.from(first), wall_out.from(first), step);
    }
  }
  log_breaks();
  // The walls' forces and moments about their points, in pair order.
  for (Wall& w : walls) w.force_n = w.moment_nm = {}, w.normal_force_n = 0;
  const WallGeometryArrays& g = in.wall_geometry;
  for (std::size_t k = 0; k < wall_pairs_.size(); ++k) {
    Wall& w = walls[static_cast<std::size_t>(wall_pairs_.j[k])];
    const auto i = static_cast<std::size_t>(wall_pairs_.i[k]);
    const Vec3 on_wall = -Vec3{in.wall_pair_forces.fx[k], in.wall_pair_forces.fy[k], in.wall_pair_forces.fz[k]};
    const Vec3 contact = spheres.position(i) + (spheres.radius[i] - 0.5 * g.overlap[k]) * Vec3{g.nx[k], g.ny[k], g.nz[k]};
    w.force_n = w.force_n + on_wall;
    w.moment_nm = w.moment_nm + cross(contact - w.point_m, on_wall);
    w.normal_force_n += dot(on_wall, Vec3{g.nx[k], g.ny[k], g.nz[k]});
  }
}

void World::move_walls() {
  for (std::size_t index = 0; index < walls.size(); ++index) {
    Wall& w = walls[index];
    if (w.servo && w.active) {
      const double area = w.loaded_area_m2();
      if (!(area > 0)) throw Error("a servo wall needs its loaded area (servo_area_m2, or a cylinder's length)");
      if (!(w.servo_max_speed_m_s > 0)) throw Error("a servo wall needs servo_max_speed_m_s > 0");
      const double error = w.normal_force_n / area - w.servo_target_stress_pa;
      const double k = wall_contact_stiffness_n_m(index);
      const double gain = w.servo_gain_m_s_per_pa > 0 ? w.servo_gain_m_s_per_pa : (k > 0 ? 0.5 * area / (k * dt_s_) : 1e300);
      // Away from the spheres while the stress is above the target.
      const double speed = std::clamp(gain * error, -w.servo_max_speed_m_s, w.servo_max_speed_m_s);
      if (w.shape == WallShape::plane) {
        w.velocity_m_s = w.velocity_m_s - dot(w.velocity_m_s, w.axis) * w.axis - speed * w.axis;
      } else if (w.shape == WallShape::cylinder_inside) {
        w.radial_speed_m_s = speed;
      } else if (w.shape == WallShape::cylinder_outside) {
        w.radial_speed_m_s = -speed;
      } else {
        throw Error("a servo wall must be a plane or a cylinder");
      }
    }
    w.radius_m += dt_s_ * w.radial_speed_m_s;
    const double rate = norm(w.spin_rad_s);
    if (rate > 0) {  // the axis (and a triangle's corners, about the pivot) turn with the spin (Rodrigues)
      const Vec3 u = (1.0 / rate) * w.spin_rad_s;
      const double a = rate * dt_s_, cos_a = std::cos(a), sin_a = std::sin(a);
      const auto turn = [&](Vec3 v) { return cos_a * v + sin_a * cross(u, v) + ((1 - cos_a) * dot(u, v)) * u; };
      const Vec3 turned = turn(w.axis);
      w.axis = (1.0 / norm(turned)) * turned;
      if (w.shape == WallShape::triangle)
        for (Vec3& v : w.vertices) v = w.point_m + turn(v - w.point_m);
    }
    const Vec3 step = dt_s_ * w.velocity_m_s;
    w.point_m = w.point_m + step;
    if (w.shape == WallShape::triangle)
      for (Vec3& v : w.vertices) v = v + step;
  }
}

void World::compute_wall_geometry() {
  Internals& in = *internals_;
  WallGeometryArrays& g = in.wall_geometry;
  const std::size_t count = wall_pairs_.size();
  const int team = threads_in_use_;
#pragma omp parallel for num_threads(team) if (team > 1) schedule(static)
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(wall_pairs_.i[k]);
    const Wall& w = walls[static_cast<std::size_t>(wall_pairs_.j[k])];
    const WallContact c = w.active ? w.contact(spheres.position(i), spheres.radius[i]) : WallContact{};
    const Vec3 v = w.velocity_at(c.point_m);
    g.nx[k] = c.normal.x, g.ny[k] = c.normal.y, g.nz[k] = c.normal.z;
    g.overlap[k] = c.overlap_m;
    g.vx[k] = v.x, g.vy[k] = v.y, g.vz[k] = v.z;
    g.feature[k] = c.feature;
  }
  if (any_mesh_) keep_one_contact_per_mesh_point();
}

namespace {

// Without a branch: a velocity's sign is as likely either way, and a
// mispredicted branch per component cost a fifth of the step.
// Selects of doubles, not an int converted: a 32-bit value in the update loop
// would halve its vectors' reach.
inline double sign_of(double v) { return dem::select(v > 0, 1.0, dem::select(v < 0, -1.0, 0.0)); }

// One component of the velocity after a step under `force` with local damping alpha.
inline double damped_velocity(double v, double force, double alpha, double to_velocity) {
  return v + (force - alpha * std::abs(force) * sign_of(v)) * to_velocity;
}

// What a step's update of the spheres reads and writes.
struct SphereArrays {
  double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz;
  const double* sums;  // the summed forces and moments, kSumStride a sphere, from sphere `lo` of update_spheres
  const double *mass, *inverse_mass, *inverse_inertia;
  const double *x_built, *y_built, *z_built;  // the positions at the last build
  const std::uint8_t* fixed;
  const std::int32_t* clump;
  const double* rolling_limit;  // type A rolling resistance's couple per sphere; nullptr: none
};

// A spin after one step of Coulomb friction in rotation: `trial` (the spin the
// other moments would give) shrunk towards zero by `slowing` (the rolling
// limit's couple times dt / I) along its own direction, and held at zero when
// the limit exceeds what would turn it: static rolling resistance.
inline void rolling_friction_spin(double& wx, double& wy, double& wz, double slowing) {
  const double size = std::sqrt(wx * wx + wy * wy + wz * wz);
  const double left = size - slowing;
  const double scale = dem::select(left > 0, left / size, 0.0);
  wx *= scale, wy *= scale, wz *= scale;
}

// Spheres [lo, hi) after a step under their summed forces and moments, as one
// vectorised loop: a fixed sphere moves at its own velocity whatever the
// forces, a clump's member waits for its clump (both by selects, not branches). Returns the largest squared move since the
// last build.
// With rolling limits the spin takes rolling_friction_spin (a separate
// instance of the loop: without them the arithmetic, and so the bits, stay).
constexpr std::size_t kUpdateChunk = 64;  // spheres an update_spheres call takes at most

template <bool kRollingLimits>
double update_spheres(std::size_t lo, std::size_t hi, const SphereArrays& a, double dt, double alpha, Vec3 g) {
  double* __restrict x = a.x;
  double* __restrict y = a.y;
  double* __restrict z = a.z;
  double* __restrict vx = a.vx;
  double* __restrict vy = a.vy;
  double* __restrict vz = a.vz;
  double* __restrict wx = a.wx;
  double* __restrict wy = a.wy;
  double* __restrict wz = a.wz;
  const double* __restrict sums = a.sums;
  const double* __restrict mass = a.mass;
  const double* __restrict inverse_mass = a.inverse_mass;
  const double* __restrict inverse_inertia = a.inverse_inertia;
  const double* __restrict x_built = a.x_built;
  const double* __restrict y_built = a.y_built;
  const double* __restrict z_built = a.z_built;
  const double* __restrict rolling_limit = a.rolling_limit;
  // Each sphere's motion as a 64-bit word: a byte-wide load in the loop below
  // would make the compiler take 32 spheres a vector and the last 32 of a
  // chunk one by one (it peels for the sums' unused slots).
  alignas(64) std::int64_t driven_of[kUpdateChunk], moves_of[kUpdateChunk];
  for (std::size_t i = lo; i < hi; ++i) {
    driven_of[i - lo] = a.fixed[i] != 0;
    moves_of[i - lo] = (a.fixed[i] == 0) & (a.clump[i] < 0);
  }
  double largest = 0;
#pragma omp simd reduction(max : largest)
  for (std::size_t i = lo; i < hi; ++i) {
    const bool driven = driven_of[i - lo] != 0, moves = moves_of[i - lo] != 0;
    const double m = mass[i];
    const double to_v = inverse_mass[i] * dt, to_w = inverse_inertia[i] * dt;
    const double new_vx = damped_velocity(vx[i], sums[kSumStride * (i - lo) + kSumFx] + m * g.x, alpha, to_v);
    const double new_vy = damped_velocity(vy[i], sums[kSumStride * (i - lo) + kSumFy] + m * g.y, alpha, to_v);
    const double new_vz = damped_velocity(vz[i], sums[kSumStride * (i - lo) + kSumFz] + m * g.z, alpha, to_v);
    double new_wx = damped_velocity(wx[i], sums[kSumStride * (i - lo) + kSumMx], alpha, to_w);
    double new_wy = damped_velocity(wy[i], sums[kSumStride * (i - lo) + kSumMy], alpha, to_w);
    double new_wz = damped_velocity(wz[i], sums[kSumStride * (i - lo) + kSumMz], alpha, to_w);
    if constexpr (kRollingLimits) rolling_friction_spin(new_wx, new_wy, new_wz, rolling_limit[i] * to_w);
    const double new_x = x[i] + new_vx * dt, new_y = y[i] + new_vy * dt, new_z = z[i] + new_vz * dt;
    // A fixed sphere keeps its velocity and spin and moves at that velocity (a grip, a driven boundary).
    vx[i] = dem::select(moves, new_vx, vx[i]);
    vy[i] = dem::select(moves, new_vy, vy[i]);
    vz[i] = dem::select(moves, new_vz, vz[i]);
    wx[i] = dem::select(moves, new_wx, wx[i]);
    wy[i] = dem::select(moves, new_wy, wy[i]);
    wz[i] = dem::select(moves, new_wz, wz[i]);
    const double to_x = dem::select(moves, new_x, dem::select(driven, x[i] + vx[i] * dt, x[i]));
    const double to_y = dem::select(moves, new_y, dem::select(driven, y[i] + vy[i] * dt, y[i]));
    const double to_z = dem::select(moves, new_z, dem::select(driven, z[i] + vz[i] * dt, z[i]));
    x[i] = to_x, y[i] = to_y, z[i] = to_z;
    const double dx = to_x - x_built[i], dy = to_y - y_built[i], dz = to_z - z_built[i];
    const double move2 = dem::select(moves || driven, dx * dx + dy * dy + dz * dz, 0.0);
    largest = largest < move2 ? move2 : largest;
  }
  return largest;
}

}  // namespace

void World::integrate() {
  Internals& in = *internals_;
  const std::size_t n = spheres.size();
  const int team = threads_in_use_;
  const PairForceArrays& sp = in.sphere_pair_forces;
  const PairForceArrays& pp = in.wall_pair_forces;
  // Type A rolling resistance: each touching pair's share of its spheres' couple limits, in pair order.
  in.rolling_limit.clear();
  if (std::any_of(models_.begin(), models_.end(), [](const auto& m) { return m->adds_rolling_limits(); })) {
    in.rolling_limit.assign(n, 0.0);
    for (std::uint8_t m : run_models_)
      models_[m]->add_rolling_limits(static_cast<const dem::ContactSet&>(pairs_).block(m), spheres, false,
                                     in.rolling_limit.data());
    for (std::uint8_t m : wall_run_models_)
      models_[m]->add_rolling_limits(static_cast<const dem::ContactSet&>(wall_pairs_).block(m), spheres, true,
                                     in.rolling_limit.data());
  }
  // Each sphere's force and moment: its pairs in pair order, then its wall
  // pairs. The same sum on any thread and in any storage order. On one thread
  // the pairs are in the sums already; on several, each thread sums its
  // spheres 64 at a time into a small buffer (the force's sign by the entry's
  // low bit, a product by +-1 is exact; the moment at the entry itself) and
  // moves them at once, while the buffer is in cache.
  const auto add_walls = [&](std::size_t i, double* sum) {
    for (std::uint32_t e = in.wall_begin[i]; e < in.wall_begin[i + 1]; ++e) {
      const std::size_t k = in.wall_entry[e];
      sum[kSumFx] += pp.fx[k], sum[kSumFy] += pp.fy[k], sum[kSumFz] += pp.fz[k];
      sum[kSumMx] += pp.mx[2 * k], sum[kSumMy] += pp.my[2 * k], sum[kSumMz] += pp.mz[2 * k];
    }
  };
  const auto give_to_clump = [&](std::size_t i, const double* sum) {  // integrate_clumps moves the members
    in.member_fx[i] = sum[kSumFx], in.member_fy[i] = sum[kSumFy], in.member_fz[i] = sum[kSumFz];
    in.member_mx[i] = sum[kSumMx], in.member_my[i] = sum[kSumMy], in.member_mz[i] = sum[kSumMz];
  };
  if (in.direct && wall_pairs_.size() > 0)
    for (std::size_t i = 0; i < n; ++i) add_walls(i, &in.sums[kSumStride * i]);
  Spheres& s = spheres;
  SphereArrays arrays{s.x.data(), s.y.data(), s.z.data(), s.vx.data(), s.vy.data(), s.vz.data(),
                      s.wx.data(), s.wy.data(), s.wz.data(), nullptr,
                      s.mass.data(), in.inverse_mass.data(), in.inverse_inertia.data(), in.x_built.data(),
                      in.y_built.data(), in.z_built.data(), s.fixed.data(), s.clump.data(),
                      in.rolling_limit.empty() ? nullptr : in.rolling_limit.data()};
  const double dt = dt_s_, alpha = settings_.damping;
  const Vec3 g = settings_.gravity_m_s2;
  const bool direct = in.direct, clumps = !clumps_.empty();
  double max_move2 = in.max_move2;
#pragma omp parallel num_threads(team) if (team > 1) reduction(max : max_move2) firstprivate(arrays)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto parts = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t lo = n * t / parts, hi = n * (t + 1) / parts;
    constexpr std::size_t kChunk = kUpdateChunk;
    alignas(64) double local[kChunk * kSumStride];
    for (std::size_t first = lo; first < hi; first += kChunk) {
      const std::size_t last = std::min(hi, first + kChunk);
      if (direct) {
        arrays.sums = &in.sums[kSumStride * first];
      } else {
        for (std::size_t i = first; i < last; ++i) {
          double fx = 0, fy = 0, fz = 0, mx = 0, my = 0, mz = 0;
          for (std::uint32_t e = in.sum_begin[i]; e < in.sum_begin[i + 1]; ++e) {
            const std::uint32_t entry = in.sum_entry[e];
            const std::size_t k = entry >> 1;
            const double sign = 1.0 - 2.0 * static_cast<double>(entry & 1u);
            fx += sign * sp.fx[k], fy += sign * sp.fy[k], fz += sign * sp.fz[k];
            mx += sp.mx[entry], my += sp.my[entry], mz += sp.mz[entry];
          }
          double* sum = &local[kSumStride * (i - first)];
          sum[kSumFx] = fx, sum[kSumFy] = fy, sum[kSumFz] = fz, sum[kSumMx] = mx, sum[kSumMy] = my, sum[kSumMz] = mz;
          add_walls(i, sum);
        }
        arrays.sums = local;
      }
      if (clumps)
        for (std::size_t i = first; i < last; ++i)
          if (s.clump[i] >= 0) give_to_clump(i, &arrays.sums[kSumStride * (i - first)]);
      max_move2 = std::max(max_move2, arrays.rolling_limit ? update_spheres<true>(first, last, arrays, dt, alpha, g)
                                                           : update_spheres<false>(first, last, arrays, dt, alpha, g));
      if (direct) std::fill_n(&in.sums[kSumStride * first], kSumStride * (last - first), 0.0);
    }
  }
  in.sums_zero = direct;
  if (!clumps_.empty()) integrate_clumps(max_move2);
  in.max_move2 = max_move2;
}

double World::force_ratio() const {
  const Internals& in = *internals_;
  const PairForceArrays& sp = in.sphere_pair_forces;
  const PairForceArrays& wp = in.wall_pair_forces;
  if (sp.fx.size() != pairs_.size() || wp.fx.size() != wall_pairs_.size()) return 0.0;
  double contact_sum = 0;
  std::size_t touching = 0;
  auto add_contact = [&](const PairForceArrays& f, const dem::ContactSet& set) {
    for (std::size_t k = 0; k < set.size(); ++k)
      if (set.flags[k] & dem::kTouching) {
        contact_sum += norm(Vec3{f.fx[k], f.fy[k], f.fz[k]});
        ++touching;
      }
  };
  add_contact(sp, pairs_);
  add_contact(wp, wall_pairs_);
  if (touching == 0) return 0.0;
  double unbalanced_sum = 0;
  std::size_t free_spheres = 0;
  for (const Vec3& f : in.clump_force) unbalanced_sum += norm(f), ++free_spheres;
  for (std::size_t i = 0; i + 1 < in.sum_begin.size(); ++i) {
    if (spheres.fixed[i] || spheres.clump[i] >= 0) continue;
    unbalanced_sum += norm(add_contact_forces(i, spheres.mass[i] * settings_.gravity_m_s2));
    ++free_spheres;
  }
  if (free_spheres == 0) return 0.0;
  return (unbalanced_sum / static_cast<double>(free_spheres)) / (contact_sum / static_cast<double>(touching));
}

Vec3 World::contact_force(std::size_t i) const {
  const Internals& in = *internals_;
  if (i + 1 >= in.sum_begin.size() || in.sphere_pair_forces.fx.size() != pairs_.size() ||
      in.wall_pair_forces.fx.size() != wall_pairs_.size())
    return {};
  return add_contact_forces(i, {});
}

Vec3 World::add_contact_forces(std::size_t i, Vec3 f) const {
  const Internals& in = *internals_;
  const PairForceArrays& sp = in.sphere_pair_forces;
  const PairForceArrays& wp = in.wall_pair_forces;
  for (std::uint32_t e = in.sum_begin[i]; e < in.sum_begin[i + 1]; ++e) {
    const std::size_t k = in.sum_entry[e] >> 1;
    const Vec3 pair_force = {sp.fx[k], sp.fy[k], sp.fz[k]};
    f = (in.sum_entry[e] & 1u) ? f - pair_force : f + pair_force;
  }
  for (std::uint32_t e = in.wall_begin[i]; e < in.wall_begin[i + 1]; ++e) {
    const std::size_t k = in.wall_entry[e];
    f = f + Vec3{wp.fx[k], wp.fy[k], wp.fz[k]};
  }
  return f;
}

double World::wall_contact_stiffness_n_m(std::size_t w) const {
  double k = 0;
  for (std::uint8_t m : wall_run_models_) {
    const dem::ConstPairBlock c = static_cast<const dem::ContactSet&>(wall_pairs_).block(m);
    for (std::size_t p = 0; p < c.size; ++p) {
      if (static_cast<std::size_t>(c.j[p]) != w || !(c.flags[p] & dem::kTouching)) continue;
      double t = 0, r = 0;
      models_[m]->stiffness(c, p, spheres.radius[static_cast<std::size_t>(c.i[p])], t, r);
      k += t;
    }
  }
  return k;
}

double World::pair_state(std::size_t k, const std::string& column) const {
  const std::vector<std::string> names = models_.at(pairs_.model.at(k))->state_columns();
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == column) return pairs_.state(k, c);
  throw Error("the pair's model " + models_[pairs_.model[k]]->name() + " has no state column " + column);
}

std::size_t World::touching_pairs() const {
  std::size_t n = 0;
  for (dem::PairFlags f : pairs_.flags) n += (f & dem::kTouching) != 0;
  return n;
}

double World::kinetic_energy() const {
  std::vector<std::size_t> order(spheres.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return spheres.id[a] < spheres.id[b]; });
  double e = 0;
  for (const Clump& c : clumps_) e += c.kinetic_energy();
  for (std::size_t i : order) {
    if (spheres.clump[i] >= 0) continue;  // counted with its clump
    const Vec3 v = spheres.velocity(i), w = spheres.spin(i);
    e += 0.5 * spheres.mass[i] * dot(v, v) + 0.5 * spheres.inertia[i] * dot(w, w);
  }
  return e;
}

std::size_t World::index_of(std::uint32_t id) const {
  for (std::size_t i = 0; i < spheres.size(); ++i)
    if (spheres.id[i] == id) return i;
  throw Error("no sphere with id " + std::to_string(id));
}

}  // namespace demcal::dem3d
