#pragma once
// The JSON form of a test result, shared by demcal-dem run and batch.
#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// status, reason, macro, parameters, seed, particles, porosity, steps, dt_s,
// density scaling (when used), wall times and particle-steps per second.
nlohmann::json result_json(const TestResult& result, const std::map<std::string, double>& parameters,
                           std::uint64_t seed);
// The curve as columns: axial_strain, stress_MPa, lateral_strain, cracks.
nlohmann::json curve_json(const TestResult& result);

}  // namespace demcal::dem
