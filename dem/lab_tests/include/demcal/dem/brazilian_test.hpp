#pragma once
// The Brazilian disc test (indirect tension).
#include <map>
#include <string>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// Brazilian disc: a disc of the specimen's width, cut from its packing, split
// between platens; macro sigma_t_MPa = 2 F_max / (pi D t).
TestResult run_brazilian(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

}  // namespace demcal::dem
