#pragma once
// Bonded bodies the closed-form tests share: a parallel bond that never breaks
// (strengths of 1e12 Pa), and a chain of disks joined by it.
#include <memory>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"

namespace demcal::dem::testing {

// A parallel bond of these moduli and stiffness ratios (linear part and bond),
// friction 0.5, that no test load breaks.
inline std::unique_ptr<ContactModel> unbreakable_parallel_bond(double modulus_pa, double kn_ks, double bond_modulus_pa,
                                                                double bond_kn_ks) {
  return ContactModelRegistry::instance().create(
      "parallel_bond",
      {{"modulus_pa", modulus_pa}, {"kn_ks", kn_ks}, {"friction", 0.5}, {"bond_modulus_pa", bond_modulus_pa},
       {"bond_kn_ks", bond_kn_ks}, {"tensile_strength_pa", 1e12}, {"shear_strength_pa", 1e12}},
      "test");
}

// n disks along x, `gap_m` apart (more than the vibration amplitudes of the
// tests) so only the bonds act, never the linear contact: a mass-spring chain
// of stiffness kn_b A = E_b t between neighbours. No damping.
inline World bonded_chain(int n, double radius_m, double gap_m, double density_kg_m3, double bond_modulus_pa) {
  WorldSettings settings;
  settings.damping = 0.0;
  World world(settings);
  world.assign(0, 0, world.add_model(unbreakable_parallel_bond(1e9, 2.0, bond_modulus_pa, 2.0)));
  for (int i = 0; i < n; ++i) world.bodies.add_disk(i * (2 * radius_m + gap_m), 0, radius_m, density_kg_m3, 1, 0);
  EXPECT_EQ(world.install_bonds(2 * gap_m, 1), static_cast<std::size_t>(n - 1));
  return world;
}

}  // namespace demcal::dem::testing
