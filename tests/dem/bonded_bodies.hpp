#pragma once
// Bonded bodies the closed-form tests share: a parallel bond that never breaks
// (strengths of 1e12 Pa), a chain of disks joined by it, and a hexagonal
// lattice with its closed-form moduli.
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

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

// columns x rows equal disks of radius_m on a hexagonal lattice, `gap_m` apart
// (odd rows shifted by half a spacing), row by row from the origin; returns
// their ids in that order. Bond them with world.install_bonds(2 * gap_m, 1).
inline std::vector<std::size_t> add_hexagonal_lattice(Bodies& bodies, int columns, int rows, double radius_m,
                                                      double gap_m, double density_kg_m3) {
  const double spacing = 2 * radius_m + gap_m, row_height = spacing * std::sqrt(3.0) / 2;
  std::vector<std::size_t> ids;
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < columns; ++col)
      ids.push_back(bodies.add_disk(col * spacing + (row % 2 ? 0.5 * spacing : 0.0), row * row_height, radius_m,
                                    density_kg_m3, 1, 0));
  return ids;
}

// A bonded hexagonal lattice is an isotropic elastic sheet; from its energy,
// per thickness t: E = 2 sqrt(3) kn (kn + ks) / ((3 kn + ks) t) and
// nu = (kn - ks) / (3 kn + ks), with kn, ks the springs between neighbours.
inline double hexagonal_lattice_modulus_pa(double kn_n_m, double ks_n_m, double thickness_m) {
  return 2 * std::sqrt(3.0) * kn_n_m * (kn_n_m + ks_n_m) / ((3 * kn_n_m + ks_n_m) * thickness_m);
}
inline double hexagonal_lattice_poisson(double kn_n_m, double ks_n_m) { return (kn_n_m - ks_n_m) / (3 * kn_n_m + ks_n_m); }

}  // namespace demcal::dem::testing
