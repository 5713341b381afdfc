#pragma once
// The registration of each built-in 3D lab test (each in its own file);
// register_builtin_tests (dem/lab_tests/src/builtin_tests.cpp) calls them.
#include "demcal/dem/lab_test.hpp"

namespace demcal::dem3d {

void register_ucs_test_3d(dem::LabTestRegistry& registry);
void register_brazilian_test_3d(dem::LabTestRegistry& registry);
void register_direct_tension_test_3d(dem::LabTestRegistry& registry);
void register_triaxial_test(dem::LabTestRegistry& registry);
void register_heap_test_3d(dem::LabTestRegistry& registry);
void register_drum_test_3d(dem::LabTestRegistry& registry);
void register_baffle_lift_test_3d(dem::LabTestRegistry& registry);

}  // namespace demcal::dem3d
