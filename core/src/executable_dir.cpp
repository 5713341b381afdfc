#include "demcal/core/executable_dir.hpp"

#include <filesystem>
#include <system_error>

namespace demcal {

std::string executable_dir() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string() : self.parent_path().string();
}

std::string default_cache_dir() {
  const std::string bin = executable_dir();
  if (bin.empty()) return "build/cache";
  return (std::filesystem::path(bin).parent_path() / "cache").string();
}

}  // namespace demcal
