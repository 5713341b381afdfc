#pragma once
// Uniaxial compression between two frictionless platens: the stress-strain
// curve and the macro values a calibration targets.
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// Packs (or loads) the specimen, bonds it, and loads it to failure. Bad input
// throws; a run that goes unstable or times out returns ok = false with the reason.
TestResult run_ucs(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// sigma_u, E (tangent where the stress first reaches half the peak), E50
// (secant there), nu (lateral over axial strain there) and the peak strain.
std::map<std::string, double> ucs_macro_values(const std::vector<CurvePoint>& curve);

}  // namespace demcal::dem
