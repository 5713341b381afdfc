// HDF5 cache of packed 3D specimens, keyed by the text of their genesis spec.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

#include "demcal/core/error.hpp"
#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/log.hpp"
#include "demcal/dem3d/genesis.hpp"

namespace demcal::dem3d {

void save_sphere_specimen(const SphereSpecimen& s, const std::string& key, const std::string& path) {
  // Write beside the target and rename, so a crash never leaves half a cache file.
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  try {
    h5::File file(temporary, h5::Mode::Truncate);
    h5::Group group = file.group("/specimen3d", true);
    group.write("x", s.x);
    group.write("y", s.y);
    group.write("z", s.z);
    group.write("radius", s.radius);
    group.set_attribute("key", key);
    group.set_attribute("vessel", std::string(s.vessel == Vessel::box ? "box" : "cylinder"));
    group.set_attribute("width_m", s.width_m);
    group.set_attribute("depth_m", s.depth_m);
    group.set_attribute("height_m", s.height_m);
    group.set_attribute("density_kg_m3", s.density_kg_m3);
    group.set_attribute("porosity", s.porosity);
    group.set_attribute("coordination_number", s.coordination_number);
    group.set_attribute("mean_overlap_ratio", s.mean_overlap_ratio);
    group.set_attribute("floaters_removed", static_cast<std::int64_t>(s.floaters_removed));
    group.set_attribute("steps", static_cast<std::int64_t>(s.steps));
    file.flush();
  } catch (...) {
    std::remove(temporary.c_str());  // no half-written file left beside the cache
    throw;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error(path + ": cannot store the packed specimen");
  }
}

SphereSpecimen load_sphere_specimen(const std::string& path, const std::string& key) {
  h5::File file(path, h5::Mode::ReadOnly);
  h5::Group group = file.group("/specimen3d", false);
  if (group.string_attribute("key") != key) throw Error(path + ": cached specimen was packed for another spec");
  SphereSpecimen s;
  s.x = group.read_doubles("x");
  s.y = group.read_doubles("y");
  s.z = group.read_doubles("z");
  s.radius = group.read_doubles("radius");
  if (s.y.size() != s.x.size() || s.z.size() != s.x.size() || s.radius.size() != s.x.size())
    throw Error(path + ": inconsistent specimen arrays");
  s.vessel = group.string_attribute("vessel") == "box" ? Vessel::box : Vessel::cylinder;
  s.width_m = group.double_attribute("width_m");
  s.depth_m = group.double_attribute("depth_m");
  s.height_m = group.double_attribute("height_m");
  s.density_kg_m3 = group.double_attribute("density_kg_m3");
  s.porosity = group.double_attribute("porosity");
  s.coordination_number = group.double_attribute("coordination_number");
  s.mean_overlap_ratio = group.double_attribute("mean_overlap_ratio");
  s.floaters_removed = static_cast<std::size_t>(group.integer_attribute("floaters_removed"));
  s.steps = static_cast<std::uint64_t>(group.integer_attribute("steps"));
  return s;
}

namespace {

// Packing takes about 1.9 kB of memory per sphere (the development machine:
// 187 MB at 100k spheres, docs/benchmarks.md). A packing that would not fit in
// this machine's memory is refused before it starts, and a large one says what
// it will take.
constexpr double kPackingBytesPerSphere = 1.9e3;

}  // namespace

void check_packing_memory(const SphereSpecimenSpec& spec, double machine_bytes) {
  const double spheres = static_cast<double>(spec.sphere_count());
  const double needed = spheres * kPackingBytesPerSphere;
  const double machine = machine_bytes > 0 ? machine_bytes
                                           : static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                                                 static_cast<double>(::sysconf(_SC_PAGESIZE));
  char text[300];
  if (machine > 0 && needed > 0.8 * machine) {
    std::snprintf(text, sizeof text,
                  "specimen: %.0f spheres need about %.1f GiB to pack, more than this machine's %.1f GiB allow; use "
                  "larger radii or a smaller specimen",
                  spheres, needed / 1073741824.0, machine / 1073741824.0);
    throw Error(text);
  }
  if (spheres >= 100000) {
    std::snprintf(text, sizeof text, "a large 3D specimen: %.0f spheres need about %.2f GiB to pack (cached after)",
                  spheres, needed / 1073741824.0);
    log::info(text);
  }
}

SphereSpecimen cached_sphere_specimen(const SphereSpecimenSpec& spec, const std::string& cache_dir) {
  spec.validate();
  check_packing_memory(spec);
  if (cache_dir.empty()) return pack_sphere_specimen(spec);
  std::error_code failed;
  std::filesystem::create_directories(cache_dir, failed);
  if (failed) throw Error("specimen cache " + cache_dir + ": cannot create the folder (" + failed.message() + ")");
  const std::string key = spec.cache_key();
  std::ostringstream name;
  name << cache_dir << "/specimen3d_" << std::hex << std::hash<std::string>{}(key) << ".h5";
  const std::string path = name.str();
  struct stat info;
  if (::stat(path.c_str(), &info) == 0) {
    try {
      return load_sphere_specimen(path, key);
    } catch (const Error& e) {
      log::warn(std::string(e.what()) + "; packing again");
    }
  }
  log::info("packing 3D specimen (" + std::to_string(spec.sphere_count()) + " spheres, seed " +
            std::to_string(spec.seed) + ") into " + path);
  SphereSpecimen s = pack_sphere_specimen(spec);
  save_sphere_specimen(s, key, path);
  return s;
}

}  // namespace demcal::dem3d
