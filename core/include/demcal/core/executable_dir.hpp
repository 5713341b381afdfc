#pragma once
// Where the running program lives, so that defaults such as the specimen
// cache sit beside the build (build/bin/.. -> build/cache) whatever folder
// the user runs from.
#include <string>

namespace demcal {

// The folder of the running executable ("" when the system does not say).
std::string executable_dir();
// The default folder of cached packed specimens: "cache" beside the
// executables' folder (build/cache for build/bin/demcal-dem); "build/cache"
// relative to the working folder when the executable's place is unknown.
std::string default_cache_dir();

}  // namespace demcal
