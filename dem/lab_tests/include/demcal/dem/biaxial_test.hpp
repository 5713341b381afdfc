#pragma once
// Biaxial test (the 2D triaxial): the specimen between two platens and two
// side walls is first brought to an isotropic confining stress by stress
// servos on all four walls; then the platens approach at the loading velocity
// while the side walls' servos hold the confinement. A series runs one
// specimen (same seed, so the same packing) per confining stress and fits the
// Mohr-Coulomb and Hoek-Brown envelopes to the peaks (strength_envelope.hpp).
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/strength_envelope.hpp"
#include "demcal/dem/test_result.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem {

// The servo of a confining wall closes this share of its stress error per
// step against the stiffness of the disks touching it (PFC's relaxation
// factor), and never moves the wall faster than this multiple of the platen
// speed (a wall that has lost its contacts must not fly off).
constexpr double kServoRelaxation = 0.5;
constexpr double kServoSpeedOverPlatenSpeed = 50.0;

// Confines and loads the specimen of `world`, whose walls are [0] bottom,
// [1] top, [2] left, [3] right (make_platen_world with side walls): all four
// servoed to `confining_stress_pa` until each wall is within 0.5 % of it and
// the force ratio below 1e-3, then the platens approach at
// loading.platen_velocity_m_s with the side walls servoed. The curve's
// stress is sigma_1 - sigma_3 (platen and side-wall forces over the current
// width and height), its strains relative to the confined specimen, the
// lateral strain from the side walls. The test's counters start once the
// confinement holds (World::start_test): bonds broken before are
// `cracks_confining`. Returns the curve, ok/reason/ended_by, the macro values
// of ucs_macro_values on that curve plus sigma_1 and sigma_3 at the peak, and
// in `steps` the confining steps (the world's counter then holds the
// loading's); loading.max_wall_s counts from `start`.
TestResult confine_and_load(World& world, double confining_stress_pa, const LoadingSpec& loading,
                            const RunOptions& options, std::chrono::steady_clock::time_point start);

// Runs the scene's series (loading.confining_stresses_MPa).
TestResult run_biaxial(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

}  // namespace demcal::dem
