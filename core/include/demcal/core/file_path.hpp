#pragma once
// Paths that one file gives relative to itself ("extends", a test list's
// scenes): resolved against the folder of the file that names them.
#include <string>

namespace demcal {

// `path` as the file `from` means it: unchanged when absolute, else in `from`'s folder.
inline std::string path_beside(const std::string& from, const std::string& path) {
  if (!path.empty() && path[0] == '/') return path;
  const std::size_t slash = from.find_last_of('/');
  return slash == std::string::npos ? path : from.substr(0, slash + 1) + path;
}

// The last part of a path (the file's own name).
inline std::string file_name(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

}  // namespace demcal
