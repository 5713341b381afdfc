// A world's state written to and read from a binary stream (world.hpp:
// write_state, read_state), for checkpoints: a run that comes to rest once
// and then tries many boundaries, or a long run that resumes.
#include <cstring>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "demcal/core/error.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {
namespace {

constexpr char kMagic[8] = {'d', 'e', 'm', 'c', 'a', 'l', 'W', '2'};
constexpr std::uint32_t kVersion = 1;

template <typename T>
void put(std::ostream& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename T>
void put(std::ostream& out, const std::vector<T>& values) {
  put(out, static_cast<std::uint64_t>(values.size()));
  if (!values.empty()) out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(sizeof(T) * values.size()));
}

void put(std::ostream& out, const std::string& text) {
  put(out, static_cast<std::uint64_t>(text.size()));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

template <typename T>
void get(std::istream& in, T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  in.read(reinterpret_cast<char*>(&value), sizeof(T));
  if (!in) throw Error("world state: the file ends early");
}

template <typename T>
void get(std::istream& in, std::vector<T>& values, std::size_t max_size) {
  std::uint64_t n = 0;
  get(in, n);
  if (n > max_size) throw Error("world state: a list longer than the world could hold (a damaged file)");
  values.resize(n);
  if (n) in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(sizeof(T) * n));
  if (!in) throw Error("world state: the file ends early");
}

void get(std::istream& in, std::string& text) {
  std::uint64_t n = 0;
  get(in, n);
  if (n > 4096) throw Error("world state: a name longer than 4096 characters (a damaged file)");
  text.resize(n);
  in.read(text.data(), static_cast<std::streamsize>(n));
  if (!in) throw Error("world state: the file ends early");
}

// A pair set as lists: ends, model, flags, then each pair's state values in its model's column order.
void put_pairs(std::ostream& out, const ContactSet& set, const std::vector<std::size_t>& layout) {
  put(out, set.i);
  put(out, set.j);
  put(out, set.model);
  put(out, set.flags);
  std::vector<double> state;
  for (std::size_t k = 0; k < set.size(); ++k)
    for (std::size_t c = 0; c < layout[set.model[k]]; ++c) state.push_back(set.state(k, c));
  put(out, state);
}

void get_pairs(std::istream& in, ContactSet& set, const std::vector<std::size_t>& layout, std::size_t bodies) {
  std::vector<std::int32_t> i, j;
  std::vector<std::uint8_t> model;
  std::vector<PairFlags> flags;
  const std::size_t most = bodies * 256 + 1024;
  get(in, i, most);
  get(in, j, most);
  get(in, model, most);
  get(in, flags, most);
  std::vector<double> state;
  get(in, state, most * kMaxStateColumns);
  if (j.size() != i.size() || model.size() != i.size() || flags.size() != i.size())
    throw Error("world state: pair lists of different lengths (a damaged file)");
  set.set_layout(layout);
  std::size_t next = 0;
  for (std::size_t k = 0; k < i.size(); ++k) {
    if (model[k] >= layout.size()) throw Error("world state: a pair of a model this world does not have");
    if (k > 0 && model[k] < model[k - 1]) throw Error("world state: pairs out of model order (a damaged file)");
    set.add(i[k], j[k], model[k]);
    set.flags[k] = flags[k];
    for (std::size_t c = 0; c < layout[model[k]]; ++c) {
      if (next >= state.size()) throw Error("world state: fewer pair state values than the models hold");
      set.state(k, c) = state[next++];
    }
  }
  if (next != state.size()) throw Error("world state: more pair state values than the models hold");
}

}  // namespace

void World::write_state(std::ostream& out) const {
  if (!clumps_.empty()) throw Error("world state: a world with clumps cannot be checkpointed yet");
  out.write(kMagic, sizeof(kMagic));
  put(out, kVersion);
  put(out, static_cast<std::uint64_t>(bodies.size()));
  put(out, layout_);
  const Bodies& b = bodies;
  for (const std::vector<double>* v : {&b.x, &b.y, &b.vx, &b.vy, &b.w, &b.fx, &b.fy, &b.moment, &b.radius, &b.mass, &b.inertia})
    put(out, *v);
  put(out, b.group);
  put(out, b.fixed);
  put(out, b.clump);
  put(out, b.id);
  put(out, static_cast<std::uint64_t>(walls.size()));
  for (const Wall& w : walls) {
    put(out, w.name);
    for (double v : {w.x0, w.y0, w.x1, w.y1, w.vx, w.vy, w.fx, w.fy, w.servo_target_stress_pa, w.servo_gain_m_s_per_pa,
                     w.servo_max_speed_m_s, w.servo_length_m, w.inward_nx, w.inward_ny})
      put(out, v);
    put(out, w.group);
    put(out, static_cast<std::uint8_t>(w.active));
    put(out, static_cast<std::uint8_t>(w.servo));
  }
  put_pairs(out, pairs_, layout_);
  put_pairs(out, wall_pairs_, layout_);
  put(out, breaks_);
  put(out, time_s_);
  put(out, steps_);
  put(out, skin_m_);
  if (!out) throw Error("world state: cannot write");
}

void World::read_state(std::istream& in) {
  if (!clumps_.empty()) throw Error("world state: a world with clumps cannot be checkpointed yet");
  char magic[sizeof(kMagic)];
  in.read(magic, sizeof(magic));
  if (!in || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) throw Error("world state: not a demcal world state");
  std::uint32_t version = 0;
  get(in, version);
  if (version != kVersion)
    throw Error("world state: version " + std::to_string(version) + ", this build reads " + std::to_string(kVersion));
  std::uint64_t n = 0;
  get(in, n);
  if (n != bodies.size())
    throw Error("world state: " + std::to_string(n) + " disks, this world has " + std::to_string(bodies.size()));
  std::vector<std::size_t> layout;
  get(in, layout, 256);
  if (layout != layout_) throw Error("world state: its contact models hold other state than this world's");
  Bodies& b = bodies;
  for (std::vector<double>* v : {&b.x, &b.y, &b.vx, &b.vy, &b.w, &b.fx, &b.fy, &b.moment, &b.radius, &b.mass, &b.inertia}) {
    get(in, *v, n);
    if (v->size() != n) throw Error("world state: a disk list of another length (a damaged file)");
  }
  get(in, b.group, n);
  get(in, b.fixed, n);
  get(in, b.clump, n);
  get(in, b.id, n);
  if (b.group.size() != n || b.fixed.size() != n || b.clump.size() != n || b.id.size() != n)
    throw Error("world state: a disk list of another length (a damaged file)");
  std::uint64_t wall_count = 0;
  get(in, wall_count);
  if (wall_count != walls.size())
    throw Error("world state: " + std::to_string(wall_count) + " walls, this world has " + std::to_string(walls.size()));
  for (Wall& w : walls) {
    get(in, w.name);
    for (double* v : {&w.x0, &w.y0, &w.x1, &w.y1, &w.vx, &w.vy, &w.fx, &w.fy, &w.servo_target_stress_pa,
                      &w.servo_gain_m_s_per_pa, &w.servo_max_speed_m_s, &w.servo_length_m, &w.inward_nx, &w.inward_ny})
      get(in, *v);
    get(in, w.group);
    std::uint8_t active = 0, servo = 0;
    get(in, active);
    get(in, servo);
    w.active = active != 0;
    w.servo = servo != 0;
  }
  get_pairs(in, pairs_, layout_, n);
  get_pairs(in, wall_pairs_, layout_, n);
  get(in, breaks_, n * 256 + 1024);
  get(in, time_s_);
  get(in, steps_);
  get(in, skin_m_);
  rebuild();  // the neighbour list, the models with pairs and the time step, from the restored pairs and positions
}

}  // namespace demcal::dem
