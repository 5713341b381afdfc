// The slope test's cache files (slope_state.hpp): the section at rest, and checkpoints of the wave run.
#include "demcal/dem/slope_state.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <unistd.h>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"

namespace demcal::dem {

// What the rest under gravity depends on: the section (the parts and profiles), the contact models as bound, the
// bond tolerance, gravity and the equilibrium's keys, the seed and the disks' order of entry; not the boundaries,
// the medium, the input or the monitors.
std::string slope_rest_key(const Scene& scene, const std::map<std::string, double>& parameters, const SlopeTestSpec& s,
                           const RunOptions& options) {
  std::ostringstream key;
  key.precision(17);
  const SlopeSpec& g = s.geometry;
  auto part = [&](const SlopePart& p) {
    key << p.name << ' ' << p.radius_min_m << ' ' << p.radius_max_m << ' ' << p.porosity << ' ' << p.density_kg_m3 << ';';
  };
  auto profile = [&](const Profile& p) {
    for (std::size_t k = 0; k < p.x.size(); ++k) key << p.x[k] << ',' << p.y[k] << ' ';
    key << ';';
  };
  key << "slope rest v1;" << g.width_m << ' ' << g.height_m << ' ' << g.thickness_m << ' ' << g.column_width_m << ';';
  part(g.bedrock);
  profile(g.bedrock_surface);
  for (const SlopeZone& z : g.zones) {
    part(z.part);
    profile(z.top);
  }
  for (const auto& [role, contact] : scene.contacts())
    key << role << '=' << contact.model << scene.bind(contact, parameters, scene.origin() + ": contacts." + role).dump() << ';';
  key << s.bond_gap_tolerance_m << ' ' << s.gravity_m_s2 << ' ' << s.equilibrium_ratio << ' ' << s.max_equilibrium_steps
      << ' ' << s.equilibrium_damping << ';' << options.seed << ' ' << options.particle_order_seed;
  return key.str();
}

std::string cache_file(const std::string& cache_dir, const std::string& prefix, const std::string& key) {
  std::ostringstream name;
  name << cache_dir << "/" << prefix << std::hex << std::hash<std::string>{}(key) << ".bin";
  return name.str();
}

// A cache file is a key (what its content depends on) and a body. Opens `path`: true when it holds `key`, the
// stream then standing after it; false when there is no file or another key's (said: a hash collision or a stale
// name), and the caller computes afresh.
static bool open_keyed(std::ifstream& in, const std::string& path, const std::string& key) {
  in.open(path, std::ios::binary);
  if (!in) return false;
  std::uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), sizeof(n));
  std::string stored(in && n < (1u << 24) ? n : 0, '\0');
  in.read(stored.data(), static_cast<std::streamsize>(stored.size()));
  if (in && stored == key) return true;
  log::warn(path + ": holds another run's state; computed afresh");
  return false;
}

// Writes `key` and what `body` writes to a temporary file renamed to `path`, so a crash or a parallel run never
// leaves half a file under the name.
static void write_keyed(const std::string& path, const std::string& key, const std::function<void(std::ostream&)>& body) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary);
    const std::uint64_t n = key.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof(n));
    out.write(key.data(), static_cast<std::streamsize>(key.size()));
    body(out);
    if (!out) throw Error(path + ": cannot write");
  }
  std::filesystem::rename(temporary, path);
}

// Once its key matched, a file that cannot be read has half replaced the world: the run fails, naming the file.
[[noreturn]] static void damaged(const std::string& path, const Error& e) {
  throw Error(path + ": damaged (" + e.what() + "); delete it to compute it afresh");
}

// True when `path` holds the rest state of `key` and the world now has it.
bool read_rest_state(World& world, const std::string& path, const std::string& key) {
  std::ifstream in;
  if (!open_keyed(in, path, key)) return false;
  try {
    world.read_state(in);
  } catch (const Error& e) {
    damaged(path, e);
  }
  return true;
}

void write_rest_state(const World& world, const std::string& path, const std::string& key) {
  write_keyed(path, key, [&](std::ostream& out) { world.write_state(out); });
}

template <typename T>
static void put_value(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}
static void put_doubles(std::ostream& out, const std::vector<double>& v) {
  put_value(out, static_cast<std::uint64_t>(v.size()));
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(sizeof(double) * v.size()));
}
template <typename T>
static void get_value(std::istream& in, T& v) {
  in.read(reinterpret_cast<char*>(&v), sizeof(T));
  if (!in) throw Error("the checkpoint ends early");
}
static void get_doubles(std::istream& in, std::vector<double>& v) {
  std::uint64_t n = 0;
  get_value(in, n);
  if (n > (1ull << 28)) throw Error("a damaged checkpoint");
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(sizeof(double) * n));
  if (!in) throw Error("the checkpoint ends early");
}

// What sets a wave run's numbers beyond its rest: every section but the limits at which a run gives up (wall time,
// a disk's speed), which change nothing in a run that stays within them; and the parameters.
std::string wave_run_key(const Scene& scene, const std::map<std::string, double>& parameters) {
  std::ostringstream key;
  key.precision(17);
  key << "slope wave v1;";
  for (const char* name : {"boundaries", "medium", "pulse", "earthquake", "monitors", "run"}) {
    nlohmann::json section = scene.section(name);
    if (section.is_object()) {
      section.erase("max_wall_s");
      section.erase("max_speed_m_s");
    }
    key << name << '=' << section.dump() << ';';
  }
  for (const auto& [name, value] : parameters) key << name << '=' << value << ' ';
  return key.str();
}

void write_wave_checkpoint(const std::string& path, const std::string& key, const WaveRunState& state) {
  write_keyed(path, key, [&](std::ostream& out) {
    state.world.write_state(out);
    put_value(out, state.forces.input_work_j());
    put_value(out, state.forces.dashpot_work_j());
    put_value(out, state.forces.applied_work_j());
    put_value(out, static_cast<std::uint64_t>(state.disks_out));
    put_value(out, static_cast<std::uint8_t>(state.input_snapshot_done));
    put_doubles(out, state.record.times);
    put_doubles(out, state.record.kinetic);
    put_value(out, static_cast<std::uint64_t>(state.record.monitors.size()));
    for (const Monitor& m : state.record.monitors) {
      put_doubles(out, m.vx);
      put_doubles(out, m.vy);
    }
  });
}

// True when `path` holds a checkpoint of this run and the state now has it.
bool read_wave_checkpoint(const std::string& path, const std::string& key, WaveRunState& state) {
  std::ifstream in;
  if (!open_keyed(in, path, key)) return false;
  try {
    state.world.read_state(in);
    double input = 0, dashpot = 0, applied = 0;
    get_value(in, input);
    get_value(in, dashpot);
    get_value(in, applied);
    state.forces.restore_work(input, dashpot, applied);
    std::uint64_t out = 0;
    std::uint8_t drawn = 0;
    get_value(in, out);
    get_value(in, drawn);
    state.disks_out = static_cast<std::size_t>(out);
    state.input_snapshot_done = drawn != 0;
    get_doubles(in, state.record.times);
    get_doubles(in, state.record.kinetic);
    std::uint64_t monitors = 0;
    get_value(in, monitors);
    if (monitors != state.record.monitors.size()) throw Error("it records other monitoring points");
    for (Monitor& m : state.record.monitors) {
      get_doubles(in, m.vx);
      get_doubles(in, m.vy);
    }
  } catch (const Error& e) {
    damaged(path, e);
  }
  return true;
}

}  // namespace demcal::dem
