#include "demcal/dem/run_settings.hpp"

namespace demcal::dem {

void apply_run_options(WorldSettings& settings, const RunOptions& options) {
  if (options.threads > 0) settings.threads = options.threads;
  if (options.min_disks_per_thread > 0) settings.min_disks_per_thread = options.min_disks_per_thread;
}

}  // namespace demcal::dem
