#pragma once
// The registration function of each built-in 2D test (each in its own file);
// register_builtin_tests (builtin_tests.cpp) calls them.
namespace demcal::dem {

class LabTestRegistry;

void register_ucs_test(LabTestRegistry& registry);
void register_brazilian_test(LabTestRegistry& registry);
void register_biaxial_test(LabTestRegistry& registry);
void register_heap_test(LabTestRegistry& registry);
void register_wave_strip_test(LabTestRegistry& registry);
void register_slope_test(LabTestRegistry& registry);

}  // namespace demcal::dem
