#pragma once
// Which scene a batch's result files belong to. The first batch into OUT
// records its scene in OUT.points/scene.owner (JSON); a batch of another scene into
// the same OUT is refused before anything is written, naming the stored
// scene, so no stored result is overwritten. Asked to, the old results are
// moved aside (never deleted) first.
#include <string>

#include "demcal/dem/scene_set.hpp"
#include "demcal/jobs/batch.hpp"

namespace demcal::jobs {

// Throws a one-line Error when OUT holds another scene's results (the scene
// recorded in OUT.points/scene.owner, or for results of older versions the
// scene file named in OUT). Writes nothing.
void check_result_files(const dem::SceneSet& scene, const BatchOptions& options);
// Records `scene` as OUT's owner once OUT.points/ exists (after the check).
void record_result_files(const dem::SceneSet& scene, const BatchOptions& options);

// Moves OUT, OUT.points/ and the CSV export (when they exist) into a new
// folder OUT_STEM.moved-K/ (the first K free) and returns that folder; "" when
// there was nothing to move.
std::string move_results_aside(const BatchOptions& options);

}  // namespace demcal::jobs
