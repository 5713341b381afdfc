// The 3D bonds against closed forms: a parallel bond's normal force, shear
// force, twisting and bending moments from its section (A = pi R_b^2,
// I = pi R_b^4 / 4, J = pi R_b^4 / 2), its breaks in tension and in shear at
// the strengths with the moment contribution factor, a contact bond's
// strengths as forces over pi r^2, every bond's forces turning with a rigid
// rotation of its pair (a flat joint's too), a bonded pair's four
// eigenfrequencies against the time step (parallel bond and flat joint), and
// a bond that holds its pair beyond the neighbour-list skin.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"
#include "bond_pair_harness.hpp"

using namespace demcal::dem3d;
namespace dem = demcal::dem;
using json = nlohmann::json;

namespace {

using bond_test::Harness;
using bond_test::kDensity;
using bond_test::kRadius;
using bond_test::rotate;
constexpr double kModulus = 1e9, kBondModulus = 2e9, kLambda = 0.8;

// A flat joint of the parallel bond's disc, 2 x 4 elements, unbreakable.
json flat_joint_parameters() {
  return {{"modulus_pa", kModulus},          {"kn_ks", 2.0},           {"friction", 0.5},
          {"joint_modulus_pa", kBondModulus}, {"joint_kn_ks", 2.5},     {"radius_multiplier", kLambda},
          {"radial_elements", 2},             {"circumferential_elements", 4},
          {"tensile_strength_pa", 1e12},      {"cohesion_pa", 1e12},    {"friction_angle_deg", 30.0},
          {"joint_friction", 0.5}};
}

json parallel_bond_parameters(double beta = 1.0) {
  return {{"modulus_pa", kModulus},        {"kn_ks", 2.0},          {"friction", 0.5},
          {"bond_modulus_pa", kBondModulus}, {"bond_kn_ks", 2.5},    {"radius_multiplier", kLambda},
          {"tensile_strength_pa", 2e6},    {"shear_strength_pa", 4e6}, {"moment_contribution", beta}};
}

const double kBondRadius = kLambda * kRadius;
const double kArea = M_PI * kBondRadius * kBondRadius;
const double kInertia = 0.25 * M_PI * std::pow(kBondRadius, 4), kPolar = 2 * kInertia;
const double kBondKn = kBondModulus / (2 * kRadius), kBondKs = kBondKn / 2.5;


}  // namespace

TEST(ParallelBond3D, ForcesAndMomentsFollowTheSection) {
  // Touching spheres along x: no linear force across the gap a pull opens.
  {
    Harness h("parallel_bond", parallel_bond_parameters(), {0, 0, 0}, {2 * kRadius, 0, 0});
    h.move(1000, {1e-3, 0, 0});  // pulled apart by 1e-8 m
    h.step();
    const double stretch = 1000 * 1e-3 * h.dt;
    EXPECT_NEAR(h.force().x, kBondKn * kArea * stretch, 1e-9 * kBondKn * kArea * stretch) << "tension pulls i to j";
  }
  {
    Harness h("parallel_bond", parallel_bond_parameters(), {0, 0, 0}, {2 * kRadius, 0, 0});
    h.move(1000, {0, 1e-3, 0});  // sheared along y by 1e-8 m
    h.step();
    const double slip = 1000 * 1e-3 * h.dt;
    EXPECT_NEAR(h.force().y, kBondKs * kArea * slip, 1e-6 * kBondKs * kArea * slip);
  }
  {
    // Bending about z: i and j turn opposite ways, so the contact points do not slide.
    Harness h("parallel_bond", parallel_bond_parameters(), {0, 0, 0}, {2 * kRadius, 0, 0});
    const double w = 1.0;
    h.move(1000, {}, {0, 0, -0.5 * w}, {0, 0, 0.5 * w});
    h.step();
    const double angle = 1000 * w * h.dt;
    EXPECT_NEAR(h.moment_i().z, kBondKn * kInertia * angle, 1e-9 * kBondKn * kInertia * angle);
    EXPECT_NEAR(norm(h.force()), 0.0, 1e-12 * kBondKn * kArea * kRadius * angle);
  }
  {
    // Twisting about the normal x.
    Harness h("parallel_bond", parallel_bond_parameters(), {0, 0, 0}, {2 * kRadius, 0, 0});
    const double w = 1.0;
    h.move(1000, {}, {-0.5 * w, 0, 0}, {0.5 * w, 0, 0});
    h.step();
    const double angle = 1000 * w * h.dt;
    EXPECT_NEAR(h.moment_i().x, kBondKs * kPolar * angle, 1e-9 * kBondKs * kPolar * angle);
  }
}

TEST(ParallelBond3D, BreaksInTensionAndInShearAtTheStrengths) {
  // Tension: sigma = -F_n / A reaches 2 MPa at a stretch of 2e6 / kn_b.
  {
    Harness h("parallel_bond", parallel_bond_parameters(), {0, 0, 0}, {2 * kRadius, 0, 0});
    const double speed = 1e-3, expected_stretch = 2e6 / kBondKn;
    int steps = 0;
    while (h.bonded() && steps < 1000000) h.move(1, {speed, 0, 0}), ++steps;
    ASSERT_FALSE(h.bonded());
    EXPECT_TRUE(h.broke_in_tension());
    EXPECT_NEAR(steps * speed * h.dt, expected_stretch, 1.01 * speed * h.dt);
    EXPECT_EQ(norm(h.force()), 0.0) << "a broken bond across a gap leaves no force";
  }
  // Shear: tau = |F_s| / A reaches 4 MPa.
  {
    Harness h("parallel_bond", parallel_bond_parameters(), {0, 0, 0}, {2 * kRadius, 0, 0});
    const double speed = 1e-3, expected_slip = 4e6 / kBondKs;
    int steps = 0;
    while (h.bonded() && steps < 1000000) h.move(1, {0, speed, speed}), ++steps;
    ASSERT_FALSE(h.bonded());
    EXPECT_FALSE(h.broke_in_tension());
    // Sliding sideways turns the contact plane (by 5e-3 rad here): a few 1e-6 of the slip.
    EXPECT_NEAR(steps * speed * std::sqrt(2.0) * h.dt, expected_slip, 1e-5 * expected_slip + 1.5 * speed * h.dt);
  }
  // Bending: sigma = beta |M_b| R_b / I; with beta = 0.5 it takes twice the angle.
  for (const double beta : {1.0, 0.5}) {
    Harness h("parallel_bond", parallel_bond_parameters(beta), {0, 0, 0}, {2 * kRadius, 0, 0});
    const double w = 10.0, expected_angle = 2e6 / (beta * kBondKn * kBondRadius);
    int steps = 0;
    while (h.bonded() && steps < 1000000) h.move(1, {}, {0, -0.5 * w, 0}, {0, 0.5 * w, 0}), ++steps;
    ASSERT_FALSE(h.bonded()) << "beta " << beta;
    EXPECT_TRUE(h.broke_in_tension()) << "bending breaks in tension, beta " << beta;
    EXPECT_NEAR(steps * w * h.dt, expected_angle, 1.01 * w * h.dt) << "beta " << beta;
  }
}

TEST(ContactBond3D, CarriesTensionUpToItsForceStrength) {
  json p = {{"modulus_pa", kModulus},       {"kn_ks", 2.0},           {"friction", 0.5},
            {"tensile_strength_pa", 2e6}, {"shear_strength_pa", 4e6}};
  Harness h("contact_bond", p, {0, 0, 0}, {1.999 * kRadius, 0, 0});  // glued at an overlap: force-free there
  h.step();
  EXPECT_EQ(norm(h.force()), 0.0);
  const double kn = M_PI * kRadius * kModulus / 2, strength_n = 2e6 * M_PI * kRadius * kRadius;
  const double speed = 1e-2;
  int steps = 0;
  double last_tension = 0;
  while (h.bonded() && steps < 1000000) {
    h.move(1, {speed, 0, 0});
    ++steps;
    if (h.bonded()) last_tension = h.force().x;
  }
  ASSERT_FALSE(h.bonded());
  EXPECT_TRUE(h.broke_in_tension());
  EXPECT_NEAR(last_tension, strength_n, kn * speed * h.dt * 1.01);
  EXPECT_NEAR(steps * speed * h.dt, strength_n / kn, 1.01 * speed * h.dt);
}

TEST(Bonds3D, ARigidRotationTurnsEveryBondForceWithThePair) {
  json cb = {{"modulus_pa", kModulus},        {"kn_ks", 2.0}, {"friction", 0.5}, {"tensile_strength_pa", 1e12},
             {"shear_strength_pa", 1e12}};
  json pb = parallel_bond_parameters();
  pb["tensile_strength_pa"] = pb["shear_strength_pa"] = 1e12;
  const json fj = flat_joint_parameters();
  for (const auto& [name, p] :
       {std::pair<std::string, json>{"contact_bond", cb}, {"parallel_bond", pb}, {"flat_joint", fj}})
    for (const Vec3 axis_raw : {Vec3{0, 0, 1}, Vec3{1, 2, 3}}) {
      const Vec3 axis = (1.0 / norm(axis_raw)) * axis_raw;
      Harness h(name, p, {0, 0, 0}, {1.99 * kRadius, 0, 0});
      // Loaded in shear, tension, bending and twist first.
      h.move(100, {-1e-3, 1e-3, 5e-4}, {0.3, -0.2, 0.1}, {-0.2, 0.4, 0.3});
      h.step();
      const Vec3 force0 = h.force(), moment0 = h.moment_i();
      ASSERT_GT(norm(force0), 0.0);
      const Vec3 x0 = h.s.position(0), x1 = h.s.position(1);
      const double omega = 1e4, steps = 20000, angle_step = omega * h.dt * 10;
      h.dt *= 10;
      for (int k = 1; k <= steps; ++k) {
        const double a = angle_step * k;
        const Vec3 p0 = rotate(x0, axis, a), p1 = rotate(x1, axis, a);
        h.s.x = {p0.x, p1.x}, h.s.y = {p0.y, p1.y}, h.s.z = {p0.z, p1.z};
        h.s.set_velocity(0, cross(omega * axis, p0));
        h.s.set_velocity(1, cross(omega * axis, p1));
        h.s.set_spin(0, omega * axis);
        h.s.set_spin(1, omega * axis);
        h.step();
      }
      const double turned = angle_step * steps;
      EXPECT_LT(norm(h.force() - rotate(force0, axis, turned)), 1e-5 * norm(force0)) << name;
      if (name != "contact_bond") {
        EXPECT_LT(norm(h.moment_i() - rotate(moment0, axis, turned)), 1e-5 * norm(moment0)) << name;
      }
    }
}

// A free bonded pair of equal touching spheres has four modes with a
// frequency: axial (w^2 = 2 K_n / m), shear with rotation (2 K_s (1/m +
// R^2/I)), twisting (2 ks_b J / I) and bending (2 kn_b I_b / I), with K the
// bond's springs, plus the contact's for a parallel bond (a flat joint
// replaces the contact). The world's step at safety 1 stays below 2 / w of
// each, and a run with every mode excited keeps its energy.
TEST(Bonds3D, TheTimeStepResolvesABondedPairsFourModes) {
  for (const std::string name : {"parallel_bond", "flat_joint"})
    for (const double kn_ks : {0.5, 2.5}) {
      json p = name == "flat_joint" ? flat_joint_parameters() : parallel_bond_parameters();
      p[name == "flat_joint" ? "joint_kn_ks" : "bond_kn_ks"] = kn_ks;
      if (name == "parallel_bond") p["tensile_strength_pa"] = p["shear_strength_pa"] = 1e12;
      WorldSettings settings;
      settings.damping = 0.0;
      settings.safety_factor = 1.0;
      World w(settings);
      w.assign(0, 0, w.add_model(ContactModelRegistry::instance().create(name, p, "test")));
      w.spheres.add_sphere({0, 0, 0}, kRadius, kDensity, 0);
      w.spheres.add_sphere({2 * kRadius, 0, 0}, kRadius, kDensity, 0);
      ASSERT_EQ(w.install_bonds(0.0, 3), 1u);
      const double m = w.spheres.mass[0], inertia = w.spheres.inertia[0];
      const double bond_ks = kBondKn / kn_ks, contact = name == "parallel_bond" ? 1.0 : 0.0;
      const double kn = contact * M_PI * kRadius * kModulus / 2 + kBondKn * kArea;
      const double ks = contact * M_PI * kRadius * kModulus / 4 + bond_ks * kArea;
      const double omega2[4] = {2 * kn / m, 2 * ks * (1 / m + kRadius * kRadius / inertia),
                                2 * bond_ks * kPolar / inertia, 2 * kBondKn * kInertia / inertia};
      for (double o2 : omega2) EXPECT_LT(w.dt_s(), 2 / std::sqrt(o2)) << name << " kn/ks " << kn_ks;
      w.spheres.set_velocity(1, {1e-4, 2e-4, -1e-4});
      w.spheres.set_spin(0, {0.3, -0.2, 0.5});
      w.spheres.set_spin(1, {-0.1, 0.4, 0.2});
      // The kinetic energy of the half-step velocities swings above the total
      // near the stability limit: its peaks, not its start, must not grow.
      double first = 0, last = 0;
      for (int k = 0; k < 20000; ++k) {
        w.step();
        double& window = k < 2000 ? first : last;
        if (k < 2000 || k >= 18000) window = std::max(window, w.kinetic_energy());
      }
      EXPECT_LT(last, 1.2 * first) << name << " kn/ks " << kn_ks << ": the pair gained energy";
      EXPECT_EQ(w.bonded_pairs(), 1u) << name;
    }
}

TEST(Bonds3D, ABondHoldsItsPairBeyondTheSkin) {
  json p = parallel_bond_parameters();
  p["tensile_strength_pa"] = p["shear_strength_pa"] = 1e12;
  WorldSettings settings;
  settings.damping = 0.0;
  settings.skin_m = 2e-6;
  World w(settings);
  w.assign(0, 0, w.add_model(ContactModelRegistry::instance().create("parallel_bond", p, "test")));
  w.spheres.add_sphere({0, 0, 0}, kRadius, kDensity, 0, 10);
  w.spheres.add_sphere({2 * kRadius, 0, 0}, kRadius, kDensity, 0, 20);
  ASSERT_EQ(w.install_bonds(0.0, 3), 1u);
  w.spheres.set_velocity(w.index_of(20), {20, 0, 0});
  double widest = 0;
  const std::uint64_t rebuilds = w.rebuilds();
  for (int k = 0; k < 20000; ++k) {
    w.step();
    const Vec3 d = w.spheres.position(w.index_of(20)) - w.spheres.position(w.index_of(10));
    widest = std::max(widest, norm(d) - 2 * kRadius);
    ASSERT_EQ(w.pairs().size(), 1u) << "step " << k;
  }
  EXPECT_GT(widest, 3 * settings.skin_m) << "the pair must open wider than the skin";
  EXPECT_GT(w.rebuilds(), rebuilds);
  EXPECT_EQ(w.bonded_pairs(), 1u);
  EXPECT_TRUE(w.breaks().empty());
}

TEST(Bonds3D, InstallingBondsNeedsAToleranceAndAFraction) {
  World w;
  EXPECT_THROW(w.install_bonds(-1.0, 1), demcal::Error);
  EXPECT_THROW(w.install_bonds(0.0, 1, 1.5), demcal::Error);
}
