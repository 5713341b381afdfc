// Neighbour list of the World: a cell grid finds the pairs closer than the
// sum of their radii plus the skin; the pairs are kept sorted by (model,
// id_i, id_j) with id_i < id_j, the disks' stable ids, so each model computes
// one contiguous block, the order of the force sums does not depend on the
// order of the disks in their arrays, and contact state carries over from the
// previous list by a merge on that order.
//
// A build is serial work between parallel steps, and genesis rebuilds often
// (2,292 times for the 22k concrete): the grid search runs on the world's
// threads, the sort is a counting sort on the lower id, and the working
// arrays and pair sets are kept from build to build.
#include <algorithm>
#include <array>
#include <cmath>

#include <omp.h>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/world.hpp"

#include "world_internals.hpp"

namespace demcal::dem {
namespace {

// (model, i, j) packed so that sorting the keys sorts the pairs.
std::uint64_t pair_key(std::uint8_t model, std::uint32_t i, std::uint32_t j) {
  return (static_cast<std::uint64_t>(model) << 56) | (static_cast<std::uint64_t>(i) << 28) | j;
}

// A pair found by the grid: its sort key and the disks' indices (i the lower id).
using Found = FoundPair;

// Pair k's key: disk-disk pairs by both ids, disk-wall pairs by the disk's id and the wall.
std::uint64_t key_of(const ContactSet& c, std::size_t k, const Bodies& b, bool wall) {
  const std::uint32_t i = b.id[static_cast<std::size_t>(c.i[k])];
  const std::uint32_t j = wall ? static_cast<std::uint32_t>(c.j[k]) : b.id[static_cast<std::size_t>(c.j[k])];
  return pair_key(c.model[k], i, j);
}

}  // namespace

std::uint8_t World::model_for(std::uint8_t a, std::uint8_t b) const {
  std::uint8_t m = table_[a][b];
  if (m == kNoModel)
    throw Error("no contact model assigned to material groups " + std::to_string(a) + " and " + std::to_string(b));
  return m;
}

void World::build_disk_pairs(ContactSet& fresh) {
  const std::size_t n = bodies.size();
  if (n < 2) return;
  double rmax = *std::max_element(bodies.radius.begin(), bodies.radius.end());
  double xmin = *std::min_element(bodies.x.begin(), bodies.x.end());
  double xmax = *std::max_element(bodies.x.begin(), bodies.x.end());
  double ymin = *std::min_element(bodies.y.begin(), bodies.y.end());
  double ymax = *std::max_element(bodies.y.begin(), bodies.y.end());
  if (!std::isfinite(xmin + xmax + ymin + ymax))
    throw Error("a disk position is not finite (the model went unstable)");
  double cell = 2.0 * rmax + skin_m_;
  // A disk far from the rest must not blow up the grid: widen the cells.
  while (((xmax - xmin) / cell + 1) * ((ymax - ymin) / cell + 1) > 4.0 * static_cast<double>(n) + 64) cell *= 2;
  const long ncx = static_cast<long>((xmax - xmin) / cell) + 1;
  const long ncy = static_cast<long>((ymax - ymin) / cell) + 1;

  ListScratch& scratch = internals_->list_scratch;
  std::vector<std::uint32_t>& cell_of = scratch.cell_of;
  std::vector<std::uint32_t>& start = scratch.cell_start;
  std::vector<std::uint32_t>& order = scratch.order;
  cell_of.resize(n);
  order.resize(n);
  start.assign(static_cast<std::size_t>(ncx * ncy + 1), 0);
  for (std::size_t i = 0; i < n; ++i) {
    long cx = static_cast<long>((bodies.x[i] - xmin) / cell), cy = static_cast<long>((bodies.y[i] - ymin) / cell);
    cell_of[i] = static_cast<std::uint32_t>(cy * ncx + cx);
    ++start[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  {
    std::vector<std::uint32_t>& fill = scratch.bucket_next;
    fill.assign(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  }
  // The disks in cell order, so the search reads its candidates one after another.
  std::vector<double>& xs = scratch.x;
  std::vector<double>& ys = scratch.y;
  std::vector<double>& rs = scratch.radius;
  std::vector<std::int32_t>& clumps = scratch.clump;
  xs.resize(n);
  ys.resize(n);
  rs.resize(n);
  clumps.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    const std::uint32_t i = order[a];
    xs[a] = bodies.x[i];
    ys[a] = bodies.y[i];
    rs[a] = bodies.radius[i];
    clumps[a] = bodies.clump[i];
  }

  // Each thread searches a band of cell rows into a list of its own; the
  // sort below makes the lists' order irrelevant.
  const int team = std::max(threads_in_use_, 1);
  std::vector<std::vector<Found>>& found_by_thread = scratch.found_by_thread;
  found_by_thread.resize(static_cast<std::size_t>(team));
  for (auto& list : found_by_thread) list.clear();  // a smaller team than asked leaves some unfilled
  std::vector<std::array<std::uint8_t, 3>>& unassigned = scratch.unassigned;
  unassigned.assign(static_cast<std::size_t>(team), {0, 0, 0});
  const std::uint32_t* id = bodies.id.data();
  const std::uint8_t* group = bodies.group.data();
  const double skin = skin_m_;
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const long size = omp_get_num_threads();
    std::vector<Found>& found = found_by_thread[t];
    // The half stencil as two runs of cells, each contiguous in the cell
    // order: this cell and its right neighbour, then the three cells above.
    for (long cy = ncy * static_cast<long>(t) / size; cy < ncy * (static_cast<long>(t) + 1) / size; ++cy)
      for (long cx = 0; cx < ncx; ++cx) {
        const long c = cy * ncx + cx;
        const std::uint32_t own_end = start[static_cast<std::size_t>(c) + 1];
        const std::uint32_t row_end = start[static_cast<std::size_t>(cx + 1 < ncx ? c + 2 : c + 1)];
        std::uint32_t above_begin = 0, above_end = 0;
        if (cy + 1 < ncy) {
          const long d = c + ncx;
          above_begin = start[static_cast<std::size_t>(cx > 0 ? d - 1 : d)];
          above_end = start[static_cast<std::size_t>(cx + 1 < ncx ? d + 2 : d + 1)];
        }
        for (std::uint32_t a = start[static_cast<std::size_t>(c)]; a < own_end; ++a) {
          const double xa = xs[a], ya = ys[a], ra = rs[a];
          const std::int32_t ca = clumps[a];
          auto consider = [&](std::uint32_t b) {
            if (ca >= 0 && ca == clumps[b]) return;  // inside one rigid clump
            const double dx = xs[b] - xa, dy = ys[b] - ya;
            const double reach = ra + rs[b] + skin;
            if (dx * dx + dy * dy >= reach * reach) return;
            const std::uint32_t i = order[a], j = order[b];
            const std::uint32_t lo = id[i] < id[j] ? i : j, hi = id[i] < id[j] ? j : i;
            // No throwing inside the threads: the pair's groups are kept
            // and model_for reports them after the search.
            const std::uint8_t m = table_[group[lo]][group[hi]];
            if (m == kNoModel) {
              unassigned[t] = {1, group[lo], group[hi]};
              return;
            }
            found.push_back({pair_key(m, id[lo], id[hi]), lo, hi});
          };
          for (std::uint32_t b = a + 1; b < row_end; ++b) consider(b);
          for (std::uint32_t b = above_begin; b < above_end; ++b) consider(b);
        }
      }
  }
  for (std::size_t t = 0; t < found_by_thread.size(); ++t)
    if (unassigned[t][0]) model_for(unassigned[t][1], unassigned[t][2]);  // throws
  // A bond holds its pair in the list however far the disks have moved apart.
  std::vector<Found>& bonded = found_by_thread[0];
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::int32_t ci = bodies.clump[static_cast<std::size_t>(pairs_.i[k])];
    const bool inside_clump = ci >= 0 && ci == bodies.clump[static_cast<std::size_t>(pairs_.j[k])];
    if ((pairs_.flags[k] & kBonded) && !inside_clump)
      bonded.push_back({key_of(pairs_, k, bodies, false), static_cast<std::uint32_t>(pairs_.i[k]),
                        static_cast<std::uint32_t>(pairs_.j[k])});
  }

  // Sorted by key: a counting sort on (model, lower id), then each bucket
  // (one disk's pairs of one model, a handful) by insertion on the higher id.
  std::uint32_t id_end = 0;
  for (const std::uint32_t v : bodies.id) id_end = std::max(id_end, v + 1);
  const std::size_t models = models_.size();
  auto bucket = [id_end](const Found& f) {
    return static_cast<std::size_t>(f.key >> 56) * id_end + static_cast<std::size_t>((f.key >> 28) & 0x0fffffffu);
  };
  std::vector<std::uint32_t>& bucket_start = scratch.bucket_start;
  bucket_start.assign(models * id_end + 1, 0);
  std::size_t total = 0;
  for (const auto& list : found_by_thread) {
    total += list.size();
    for (const Found& f : list) ++bucket_start[bucket(f) + 1];
  }
  for (std::size_t b = 1; b < bucket_start.size(); ++b) bucket_start[b] += bucket_start[b - 1];
  std::vector<Found>& found = scratch.found;
  found.resize(total);
  {
    std::vector<std::uint32_t>& next = scratch.bucket_next;
    next.assign(bucket_start.begin(), bucket_start.end() - 1);
    for (const auto& list : found_by_thread)
      for (const Found& f : list) found[next[bucket(f)]++] = f;
  }
  for (std::size_t b = 0; b + 1 < bucket_start.size(); ++b)
    for (std::uint32_t k = bucket_start[b] + 1; k < bucket_start[b + 1]; ++k)
      for (std::uint32_t m = k; m > bucket_start[b] && found[m].key < found[m - 1].key; --m)
        std::swap(found[m], found[m - 1]);
  found.erase(std::unique(found.begin(), found.end(), [](const Found& a, const Found& b) { return a.key == b.key; }),
              found.end());
  std::vector<std::size_t> per_model(models, 0);
  for (const Found& f : found) ++per_model[static_cast<std::size_t>(f.key >> 56)];
  fresh.assign_blocks(per_model);
  for (std::size_t k = 0; k < found.size(); ++k) {
    fresh.i[k] = static_cast<std::int32_t>(found[k].i);
    fresh.j[k] = static_cast<std::int32_t>(found[k].j);
  }
}

void World::build_wall_pairs(ContactSet& fresh) {
  std::vector<Found> found;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& wall = walls[w];
    if (!wall.active) continue;
    const double ex = wall.x1 - wall.x0, ey = wall.y1 - wall.y0;
    const double length2 = ex * ex + ey * ey;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      double s = length2 > 0 ? ((bodies.x[i] - wall.x0) * ex + (bodies.y[i] - wall.y0) * ey) / length2 : 0.0;
      s = std::clamp(s, 0.0, 1.0);
      const double dx = bodies.x[i] - (wall.x0 + s * ex), dy = bodies.y[i] - (wall.y0 + s * ey);
      const double reach = bodies.radius[i] + skin_m_;
      if (dx * dx + dy * dy >= reach * reach) continue;
      found.push_back({pair_key(model_for(bodies.group[i], wall.group), bodies.id[i], static_cast<std::uint32_t>(w)),
                       static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(w)});
    }
  }
  std::sort(found.begin(), found.end());
  fresh.reserve(found.size());
  for (const Found& f : found)
    fresh.add(static_cast<std::int32_t>(f.i), static_cast<std::int32_t>(f.j), static_cast<std::uint8_t>(f.key >> 56));
}

// Pairs already known keep their state; new ones get their model's constants.
void World::merge_into(ContactSet& fresh, ContactSet& old, bool wall) {
  std::size_t o = 0;
  PairBlock block;
  std::uint8_t block_model = kNoModel;
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    const std::uint64_t key = key_of(fresh, k, bodies, wall);
    while (o < old.size() && key_of(old, o, bodies, wall) < key) ++o;
    if (o < old.size() && key_of(old, o, bodies, wall) == key) {
      fresh.copy_state(k, old, o);
      continue;
    }
    const std::size_t i = static_cast<std::size_t>(fresh.i[k]), j = static_cast<std::size_t>(fresh.j[k]);
    PairInfo info;
    info.radius_i = bodies.radius[i];
    info.group_i = bodies.group[i];
    info.wall = wall;
    info.radius_j = wall ? 0.0 : bodies.radius[j];
    info.group_j = wall ? walls[j].group : bodies.group[j];
    info.mass_i_kg = moving_mass(i);
    info.mass_j_kg = wall ? 0.0 : moving_mass(j);
    if (fresh.model[k] != block_model) {
      block_model = fresh.model[k];
      block = fresh.block(block_model);
    }
    models_[block_model]->initialise(block, k - fresh.begin(block_model), info, settings_.thickness_m);
  }
}

double World::attachment_gap_m() const {
  double radius_max = 0;
  for (double r : bodies.radius) radius_max = std::max(radius_max, r);
  double gap = 0;
  for (const auto& model : models_) gap = std::max(gap, model->attachment_gap_m(radius_max));
  return gap;
}

void World::rebuild() {
  // A pair still pulling across a gap the skin does not cover would leave the
  // list at this build and lose its force and history.
  const double attached = attachment_gap_m();
  if (skin_m_ <= 0) {
    if (settings_.skin_m > 0) {
      skin_m_ = settings_.skin_m;
    } else {
      double sum = 0;
      for (double r : bodies.radius) sum += r;
      skin_m_ = bodies.size() ? 0.25 * sum / static_cast<double>(bodies.size()) : 0.0;
    }
  }
  // The default skin follows the models' need as the disks grow; one set by hand must already cover it.
  if (settings_.skin_m <= 0) skin_m_ = std::max(skin_m_, 2.0 * attached);
  if (attached > 0 && attached >= skin_m_)
    throw Error("the neighbour-list skin (" + format_double(skin_m_) + " m) does not exceed the largest gap a contact "
                "model's pairs pull across (" + format_double(attached) +
                " m, JKR's delta_c at the largest disk): raise the skin above it");
  // Built in the last but one build's sets (their storage kept), then swapped in.
  ContactSet& fresh_pairs = internals_->list_scratch.pairs;
  ContactSet& fresh_walls = internals_->list_scratch.wall_pairs;
  fresh_pairs.set_layout(layout_);
  fresh_walls.set_layout(layout_);
  build_disk_pairs(fresh_pairs);
  build_wall_pairs(fresh_walls);
  merge_into(fresh_pairs, pairs_, false);
  merge_into(fresh_walls, wall_pairs_, true);
  std::swap(pairs_, fresh_pairs);
  std::swap(wall_pairs_, fresh_walls);

  // The models that have pairs, in pair order (each model's pairs are one block).
  auto runs = [](const ContactSet& c, std::vector<std::uint8_t>& models) {
    models.clear();
    for (std::size_t k = 0; k < c.size(); ++k)
      if (models.empty() || models.back() != c.model[k]) models.push_back(c.model[k]);
  };
  runs(pairs_, run_models_);
  runs(wall_pairs_, wall_run_models_);

  x_built_ = bodies.x;
  y_built_ = bodies.y;
  wall_built_.resize(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) wall_built_[w] = {walls[w].x0, walls[w].y0};
  max_disk_move2_ = 0;
  // Threads: as asked, but at most one per min_disks_per_thread disks (and
  // 255: a disk's owner is a byte).
  const std::size_t asked = static_cast<std::size_t>(settings_.threads > 0 ? settings_.threads : omp_get_max_threads());
  const std::size_t fit = bodies.size() / std::max<std::size_t>(settings_.min_disks_per_thread, 1);
  threads_in_use_ = static_cast<int>(std::max<std::size_t>(1, std::min({asked, fit, std::size_t{255}})));
  if (threads_in_use_ > 1) build_thread_partition();
  ++rebuilds_;
  built_ = true;
  update_time_step();
}

}  // namespace demcal::dem
