#pragma once
// PFC3D's material pressure: the packed specimen, still in its vessel, is
// brought to an isotropic stress by servo walls at the design point's own
// contact stiffness (frictionless, as PFC's packing phase), bonded there with
// every contact keeping its force, and then relaxed out of the vessel, so its
// bonds hold the stress locked in the grains (Potyondy & Cundall 2004; PFC's
// material-modeling support). A packing is cached at one genesis stiffness,
// so this stage runs per design point, after the cache.
#include <map>
#include <string>

#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/genesis.hpp"
#include "demcal/dem3d/world.hpp"

namespace demcal::dem3d {

// specimen.locked_in_stress_pa at `parameters`; 0 when the scene has none.
double locked_in_stress_pa(const dem::Scene& scene, const std::map<std::string, double>& parameters);

struct PressuredSpecimen {
  SphereSpecimen specimen;  // where the servo left the spheres, the vessel at its new size
  std::string reason;       // why the stage failed; empty when it held
};

// The specimen in its vessel (a cylinder's two platens and side, or a box's
// six faces) under the scene's contact models with friction 0, every wall
// servoed to `stress_pa` until each holds it within 0.5 % with the spheres at
// rest (force ratio 1e-3). The result is moved so its vessel starts at the
// origin again; its porosity is the one in the new vessel, and its
// locked_in_stress_pa the mean of the walls' stresses. `info` receives the
// stage's steps and the porosity change. The reason, and no specimen, when
// it is not held within 2,000,000 steps or loading.max_wall_s, or the
// spheres' positions stop being finite.
PressuredSpecimen install_material_pressure(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                                            const SphereSpecimen& specimen, double stress_pa,
                                            const dem::RunOptions& options, std::map<std::string, double>& info);

// A test's specimen into `specimen`: the cached packing of the scene's
// specimen section at `parameters` and options.seed, pressured when the scene
// asks for a locked-in stress (the stage's figures in result.specimen_info).
// False, with result.reason, when the stage fails.
bool test_specimen(const dem::Scene& scene, const std::map<std::string, double>& parameters,
                   const dem::RunOptions& options, dem::TestResult& result, SphereSpecimen& specimen);

// After the bonds are installed on a pressured specimen: lifts every wall off
// (inactive), cycles until the spheres are at rest (force ratio 1e-3), then
// sets each wall back where it touches the relaxed specimen: a plane moved
// along its normal, a cylinder's radius. The reason when it does not settle
// within `max_steps`; empty otherwise.
std::string relax_out_of_vessel(World& world, std::uint64_t max_steps);

}  // namespace demcal::dem3d
