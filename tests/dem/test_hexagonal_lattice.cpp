// A regular hexagonal packing of equal disks joined by bonds is an isotropic
// elastic sheet (bonded_bodies.hpp: E = 2 sqrt(3) kn (kn + ks) / ((3 kn + ks) t),
// nu = (kn - ks) / (3 kn + ks)). A block under small uniaxial strain must
// reproduce both within 2 %.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "bonded_bodies.hpp"

using namespace demcal::dem;

TEST(HexagonalLattice, UniaxialStrainGivesTheLatticeModuli) {
  const double r = 1e-3, gap = 1e-6, bond_modulus = 4e9, ratio = 2.0;  // gap > the imposed shortening (2e-7 m), so no linear contact forms
  const int columns = 40, rows = 20;
  WorldSettings settings;
  settings.damping = 0.7;
  World world(settings);
  world.assign(0, 0, world.add_model(demcal::dem::testing::unbreakable_parallel_bond(1e9, 2.0, bond_modulus, ratio)));
  const double spacing = 2 * r + gap;
  const std::vector<std::size_t> ids = demcal::dem::testing::add_hexagonal_lattice(world.bodies, columns, rows, r, gap, 2650);
  std::vector<std::size_t> left, right;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (k % columns == 0) left.push_back(ids[k]);
    if (k % columns == columns - 1) right.push_back(ids[k]);
  }
  world.install_bonds(2 * gap, 1);
  // Bond springs (no linear contact: the disks never touch): kn = kn_b A = E_b t.
  const double kn = bond_modulus * 1.0, ks = kn / ratio;

  // Bond forces grow with the velocities (incremental law), so the strain is
  // applied by driving the end disks: the right ends move left at constant
  // speed for `loading` steps (the others start on the affine velocity field),
  // then hold while the sheet settles; the end disks are held in x, free in y.
  const double strain = -1e-4;
  std::vector<double> x_start = world.bodies.x, y_start = world.bodies.y;
  const double length = world.bodies.x[right[0]] - world.bodies.x[left[0]];
  world.refresh();
  const int loading = 4000, settling = 16000;
  const double speed = strain * length / (loading * world.dt_s());
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    world.bodies.vx[i] = speed * (world.bodies.x[i] - x_start[left[0]]) / length;
  double axial_force = 0;
  for (int s = 0; s < loading + settling; ++s) {
    const double end_speed = s < loading ? speed : 0.0;
    const double shift = speed * world.dt_s() * std::min(s, loading);
    for (std::size_t i : left) world.bodies.vx[i] = 0;
    for (std::size_t i : right) world.bodies.vx[i] = end_speed;
    world.step();
    axial_force = 0;
    for (std::size_t i : left) world.bodies.x[i] = x_start[i];
    for (std::size_t i : right) {
      axial_force += world.bodies.fx[i];
      world.bodies.x[i] = x_start[i] + shift + end_speed * world.dt_s();
    }
  }
  // Strains measured between disks of the middle columns / the top and bottom rows.
  auto mean_of = [&](const std::vector<double>& v, auto pick) {
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < world.bodies.size(); ++i)
      if (pick(i)) {
        sum += v[i];
        ++n;
      }
    return sum / n;
  };
  auto column = [&](int c) { return [=](std::size_t i) { return static_cast<int>(i) % columns == c; }; };
  auto row_of = [&](int rr) {
    return [=](std::size_t i) {
      int col = static_cast<int>(i) % columns;
      return static_cast<int>(i) / columns == rr && col > columns / 4 && col < 3 * columns / 4;
    };
  };
  const double exx = (mean_of(world.bodies.x, column(30)) - mean_of(world.bodies.x, column(10))) /
                         (mean_of(x_start, column(30)) - mean_of(x_start, column(10))) - 1;
  const double eyy = (mean_of(world.bodies.y, row_of(rows - 1)) - mean_of(world.bodies.y, row_of(0))) /
                         (mean_of(y_start, row_of(rows - 1)) - mean_of(y_start, row_of(0))) - 1;
  // Each row carries its force over a height of one row spacing.
  const double stress = -axial_force / (rows * spacing * std::sqrt(3.0) / 2 * 1.0);
  const double E = stress / exx;
  const double nu = -eyy / exx;
  const double E_expected = demcal::dem::testing::hexagonal_lattice_modulus_pa(kn, ks, 1.0);
  const double nu_expected = demcal::dem::testing::hexagonal_lattice_poisson(kn, ks);
  EXPECT_NEAR(E, E_expected, 0.02 * E_expected);
  EXPECT_NEAR(nu, nu_expected, 0.02 * nu_expected);
  EXPECT_NEAR(exx, strain, 0.05 * std::abs(strain));
}
