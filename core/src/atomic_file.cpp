#include "demcal/core/atomic_file.hpp"

#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "demcal/core/error.hpp"

namespace demcal {

void write_file_atomically(const std::string& path, const std::string& content) {
  std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path + ": cannot open for writing");
    out << content;
    out.flush();
    if (!out) throw Error(path + ": write failed");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error(path + ": cannot move the finished file into place");
  }
}

}  // namespace demcal
