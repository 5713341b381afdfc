// Bond installation makes a packing force-free as it lies (PFC's "remove
// overlap only"): the overlaps genesis leaves never become forces of the
// test's stiffness, and each contact measures its force from the overlap it
// had when the specimen was bonded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/genesis.hpp"
#include "demcal/dem/world.hpp"
#include "imposed_motion.hpp"

using namespace demcal::dem;
using demcal::dem::testing::imposed_step;

namespace {

nlohmann::json parallel_bond(double modulus_pa) {
  return {{"modulus_pa", modulus_pa}, {"kn_ks", 2.0},          {"friction", 0.5},
          {"bond_modulus_pa", modulus_pa}, {"bond_kn_ks", 2.0}, {"tensile_strength_pa", 1e7},
          {"shear_strength_pa", 1e7}};
}

// The disks of a dense packing (porosity 0.12, so overlapping) in a world
// without walls, `model` between every pair, bonds installed.
World packed_world(const std::string& model, const nlohmann::json& parameters) {
  SpecimenSpec spec;
  spec.width_m = 0.01;
  spec.height_m = 0.02;
  spec.porosity = 0.12;
  spec.radius_min_m = 3e-4;
  spec.radius_max_m = 4.5e-4;
  spec.seed = 7;
  const Specimen s = pack_specimen(spec);
  EXPECT_GT(s.mean_overlap_ratio, 1e-3);  // the packing really does overlap
  WorldSettings settings;
  settings.damping = 0;  // damping would hide a force
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create(model, parameters, "test")));
  for (std::size_t i = 0; i < s.size(); ++i) world.bodies.add_disk(s.x[i], s.y[i], s.radius[i], 2000, 1, 0);
  world.install_bonds(1e-2 * spec.radius_min_m, 1);
  return world;
}

double fastest_disk_m_s(const World& world) {
  double fastest = 0;
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    fastest = std::max(fastest, std::hypot(world.bodies.vx[i], world.bodies.vy[i]));
  return fastest;
}

}  // namespace

TEST(ForceFreeInstallation, ABondedDenseSpecimenStaysAtRestAtAnyStiffness) {
  // Overlaps of about a per cent of a radius at 50 GPa would throw disks off at
  // metres per second within a few hundred steps; force-free, nothing moves.
  for (double modulus : {1e9, 5e10}) {
    World world = packed_world("parallel_bond", parallel_bond(modulus));
    world.run(300);
    EXPECT_EQ(fastest_disk_m_s(world), 0.0) << "modulus " << modulus;
    EXPECT_EQ(world.kinetic_energy(), 0.0);
  }
}

TEST(ForceFreeInstallation, AnUnbondedPackingStartsForceFreeToo) {
  World world = packed_world("linear", {{"modulus_pa", 5e10}, {"kn_ks", 2.0}, {"friction", 0.5}});
  world.run(300);
  EXPECT_EQ(fastest_disk_m_s(world), 0.0);
  // Every pair that overlapped keeps that overlap as its reference.
  std::size_t referenced = 0;
  for (std::size_t k = 0; k < world.pairs().size(); ++k) referenced += world.pair_state(k, "reference_overlap_m") > 0;
  EXPECT_GT(referenced, world.bodies.size());  // more than one contact per disk
}

TEST(ForceFreeInstallation, ForceGrowsFromTheInstalledOverlapAtBothSpringsInParallel) {
  // Two disks overlapping by delta0 when bonded, then pushed together by d:
  // F = (kn + kn_b A) d, not kn (delta0 + d) + kn_b A d.
  const double radius = 1e-3, delta0 = 2e-5, dt = 1e-8, v = 0.5, modulus = 1e9;
  WorldSettings settings;
  settings.fixed_dt_s = dt;
  settings.damping = 0;
  World world(settings);
  world.assign(0, 0, world.add_model(ContactModelRegistry::instance().create("parallel_bond", parallel_bond(modulus), "test")));
  world.bodies.add_disk(0, 0, radius, 2650, 1, 0);
  world.bodies.add_disk(2 * radius - delta0, 0, radius, 2650, 1, 0);
  world.bodies.fixed[0] = world.bodies.fixed[1] = 1;
  ASSERT_EQ(world.install_bonds(1e-9, 1), 1u);
  EXPECT_NEAR(world.pair_state(0, "reference_overlap_m"), delta0, 1e-12 * delta0);
  // kn = 2 r t E / (2 r) = E t; kn_b A = E / (2 r) * 2 r t = E t.
  const double kn = modulus, kn_bond_area = modulus;
  for (int step = 1; step <= 200; ++step) {
    imposed_step(world, -v, 0, 0);
    const double d = v * dt * step;
    // Disk 0 is pushed away from disk 1 (towards -x): the force on it is -F.
    // The contact sees the positions at the step's start (one step behind);
    // the bond integrates this step's velocity.
    const double expected = kn * (d - v * dt) + kn_bond_area * d;
    ASSERT_NEAR(-world.bodies.fx[0], expected, 1e-6 * expected) << step;
  }
}
