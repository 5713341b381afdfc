// HDF5 cache of packed specimens, keyed by the text of their genesis spec.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

#include "demcal/core/error.hpp"
#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/log.hpp"
#include "demcal/dem/genesis.hpp"

namespace demcal::dem {

void save_specimen(const Specimen& s, const std::string& key, const std::string& path) {
  // Write beside the target and rename, so a crash never leaves half a cache file.
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    h5::File file(temporary, h5::Mode::Truncate);
    h5::Group group = file.group("/specimen", true);
    group.write("x", s.x);
    group.write("y", s.y);
    group.write("radius", s.radius);
    group.set_attribute("key", key);
    group.set_attribute("width_m", s.width_m);
    group.set_attribute("height_m", s.height_m);
    group.set_attribute("thickness_m", s.thickness_m);
    group.set_attribute("density_kg_m3", s.density_kg_m3);
    group.set_attribute("porosity", s.porosity);
    group.set_attribute("coordination_number", s.coordination_number);
    group.set_attribute("mean_overlap_ratio", s.mean_overlap_ratio);
    group.set_attribute("floaters_removed", static_cast<std::int64_t>(s.floaters_removed));
    group.set_attribute("steps", static_cast<std::int64_t>(s.steps));
    file.flush();
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error(path + ": cannot store the packed specimen");
  }
}

Specimen load_specimen(const std::string& path, const std::string& key) {
  h5::File file(path, h5::Mode::ReadOnly);
  h5::Group group = file.group("/specimen", false);
  if (group.string_attribute("key") != key) throw Error(path + ": cached specimen was packed for another spec");
  Specimen s;
  s.x = group.read_doubles("x");
  s.y = group.read_doubles("y");
  s.radius = group.read_doubles("radius");
  if (s.y.size() != s.x.size() || s.radius.size() != s.x.size()) throw Error(path + ": inconsistent specimen arrays");
  s.width_m = group.double_attribute("width_m");
  s.height_m = group.double_attribute("height_m");
  s.thickness_m = group.double_attribute("thickness_m");
  s.density_kg_m3 = group.double_attribute("density_kg_m3");
  s.porosity = group.double_attribute("porosity");
  s.coordination_number = group.double_attribute("coordination_number");
  s.mean_overlap_ratio = group.double_attribute("mean_overlap_ratio");
  s.floaters_removed = static_cast<std::size_t>(group.integer_attribute("floaters_removed"));
  s.steps = static_cast<std::uint64_t>(group.integer_attribute("steps"));
  return s;
}

namespace {

// What packing a large specimen will ask for, said before it starts. From the
// development machine (docs/benchmarks.md): about 2.1 ms of packing per disk
// on one thread at 9-19 thousand disks (growing somewhat faster than the
// count), and about 1 kB of memory per disk for a bonded run.
void say_large_specimen(std::size_t disks) {
  if (disks < 100000) return;
  const double gib = static_cast<double>(disks) * 1.0e3 / (1024.0 * 1024.0 * 1024.0);
  const double minutes = static_cast<double>(disks) * 2.1e-3 / 60.0;
  char text[400];
  std::snprintf(text, sizeof text,
                "a large specimen: %zu disks need about %.1f GiB of memory, and packing them takes at least %.0f min "
                "(the development machine's 2.1 ms per disk on one thread; it is cached for later runs)",
                disks, gib, minutes);
  log::info(text);
}

}  // namespace

Specimen cached_specimen(const SpecimenSpec& spec, const std::string& cache_dir) {
  if (cache_dir.empty()) {
    say_large_specimen(spec.disk_count());
    return pack_specimen(spec);
  }
  // With its parents (a run from another folder than the repository's names
  // build/cache relative to where it runs); a folder that cannot be made is
  // said as such, not as an HDF5 file that cannot be opened.
  std::error_code failed;
  std::filesystem::create_directories(cache_dir, failed);
  if (failed) throw Error("specimen cache " + cache_dir + ": cannot create the folder (" + failed.message() + ")");
  const std::string key = spec.cache_key();
  std::ostringstream name;
  name << cache_dir << "/specimen_" << std::hex << std::hash<std::string>{}(key) << ".h5";
  const std::string path = name.str();
  struct stat info;
  if (::stat(path.c_str(), &info) == 0) {
    try {
      return load_specimen(path, key);
    } catch (const Error& e) {
      log::warn(std::string(e.what()) + "; packing again");
    }
  }
  log::info("packing specimen (" + std::to_string(spec.disk_count()) + " disks, seed " + std::to_string(spec.seed) +
            ") into " + path);
  say_large_specimen(spec.disk_count());
  Specimen s = pack_specimen(spec);
  save_specimen(s, key, path);
  return s;
}

}  // namespace demcal::dem
