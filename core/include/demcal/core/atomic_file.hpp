#pragma once
// Writes a whole file so that readers (and a crash) see either the old file or
// the complete new one: write to a temporary sibling, flush, then rename.
#include <string>

namespace demcal {

void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace demcal
