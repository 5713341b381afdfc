#include "demcal/dem/builtin_tests.hpp"

#include "demcal/dem/external_test.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem3d/lab_tests_3d.hpp"

namespace demcal::dem {

// The registry lives where the engines' tests are linked, so the scene layer
// that declares it depends on no engine.
LabTestRegistry& LabTestRegistry::instance() {
  static LabTestRegistry registry = [] {
    LabTestRegistry r;
    register_builtin_tests(r);
    return r;
  }();
  return registry;
}

void register_builtin_tests(LabTestRegistry& registry) {
  register_ucs_test(registry);
  register_brazilian_test(registry);
  register_biaxial_test(registry);
  register_external_test(registry);
  register_heap_test(registry);
  register_wave_strip_test(registry);
  register_slope_test(registry);
  dem3d::register_ucs_test_3d(registry);
  dem3d::register_brazilian_test_3d(registry);
  dem3d::register_triaxial_test(registry);
  dem3d::register_heap_test_3d(registry);
  dem3d::register_drum_test_3d(registry);
  dem3d::register_baffle_lift_test_3d(registry);
  dem3d::register_direct_tension_test_3d(registry);
}

}  // namespace demcal::dem
