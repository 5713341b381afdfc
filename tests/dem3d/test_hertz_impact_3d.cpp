// Hertz-Mindlin in 3D, head-on impacts of two equal spheres and of a sphere on
// a plane: Hertz's collision time without damping; the set restitution
// returned within 3 % at the powder scenes' step (8 % of the Rayleigh step)
// at 0.3-3 m/s (the model's restitution does not depend on the speed), on a
// wall of the same material and, up to the scenes' speeds, of steel; and a
// pressed sphere at a restitution near zero coming to rest at the engine's
// own step.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

struct Material {
  double radius_m, density_kg_m3, shear_modulus_pa, poisson;
  double rayleigh_step_s() const {
    return M_PI * radius_m * std::sqrt(density_kg_m3 / shear_modulus_pa) / (0.1631 * poisson + 0.8766);
  }
};

// He et al.'s powder as the shipped 3D scenes set it.
constexpr Material kPowder{1.5e-3, 60, 3.5e5, 0.4};

struct Impact {
  double restitution;  // the speed after over the speed before
  double contact_s;    // how long the pair touched
};

// Two spheres meeting at `speed_m_s` (or one on a plane); the step `fixed_dt_s`.
// `steel_wall`: the plane is the powder scenes' steel (G 7.9e10 Pa, nu 0.3).
Impact impact(const Material& m, double restitution, bool wall, double speed_m_s, double fixed_dt_s,
              bool steel_wall = false) {
  WorldSettings settings;
  settings.damping = 0.0;
  settings.fixed_dt_s = fixed_dt_s;
  World world(settings);
  const nlohmann::json p = {{"shear_modulus_pa", m.shear_modulus_pa}, {"poisson", m.poisson},
                            {"restitution", restitution}, {"friction", 0.5}};
  nlohmann::json q = p;
  if (steel_wall) q["shear_modulus_2_pa"] = 7.9e10, q["poisson_2"] = 0.3;
  auto& registry = ContactModelRegistry::instance();
  world.assign(0, 0, world.add_model(registry.create("hertz_mindlin", p, "test")));
  world.assign(0, 1, world.add_model(registry.create("hertz_mindlin", q, "test")));
  const double r = m.radius_m, gap = 0.01 * r;
  world.spheres.add_sphere({0, 0, 0}, r, m.density_kg_m3, 0);
  if (wall) {
    world.walls.push_back(make_plane({r + gap, 0, 0}, {-1, 0, 0}, 1));
  } else {
    world.spheres.add_sphere({2 * r + gap, 0, 0}, r, m.density_kg_m3, 0);
    world.spheres.set_velocity(1, {-0.5 * speed_m_s, 0, 0});
  }
  world.spheres.set_velocity(0, {wall ? speed_m_s : 0.5 * speed_m_s, 0, 0});
  world.refresh();
  // Until the pair has touched and let go (its flag, set by the model).
  Impact out{0, 0};
  bool touched = false;
  for (int k = 0; k < 1000000; ++k) {
    world.step();
    const demcal::dem::ContactSet& set = wall ? world.wall_pairs() : world.pairs();
    const bool touching = set.size() > 0 && (set.flags[0] & demcal::dem::kTouching);
    if (touching) out.contact_s += world.dt_s();
    touched = touched || touching;
    if (touched && !touching) break;
  }
  EXPECT_TRUE(touched);
  out.restitution = -(world.spheres.vx[0] - (wall ? 0.0 : world.spheres.vx[1])) / speed_m_s;
  return out;
}

}  // namespace

TEST(HertzImpact3D, WithoutDampingTheContactLastsHertzsDuration) {
  const Material m{1e-3, 2650, 1e8, 0.25};
  const double speed = 0.5;
  for (bool wall : {false, true}) {
    const Impact done = impact(m, 1.0, wall, speed, 0.02 * m.rayleigh_step_s());
    EXPECT_NEAR(done.restitution, 1.0, 0.005);
    // Hertz's duration 2.87 (m*^2 / (R* E*^2 v))^(1/5).
    const double mass = m.density_kg_m3 * 4.0 / 3.0 * M_PI * std::pow(m.radius_m, 3);
    const double m_eff = wall ? mass : mass / 2, r_eff = wall ? m.radius_m : m.radius_m / 2;
    const double e_eff = 1.0 / (2 * (1 - m.poisson * m.poisson) / (2 * m.shear_modulus_pa * (1 + m.poisson)));
    const double expected = 2.87 * std::pow(m_eff * m_eff / (r_eff * e_eff * e_eff * speed), 0.2);
    EXPECT_NEAR(done.contact_s, expected, 0.02 * expected) << (wall ? "on a wall" : "between spheres");
  }
}

// Before the normal dashpot was fed the velocity at the step's own time, e 0.1
// came back 9 % low (pairs) at this step.
TEST(HertzImpact3D, ImpactsReturnTheSetRestitutionWithinThreePercentAtThePowderStep) {
  for (double e : {0.1, 0.3, 0.6, 0.9})
    for (double speed : {0.3, 1.0, 3.0})
      for (bool wall : {false, true}) {
        const double returned = impact(kPowder, e, wall, speed, 0.08 * kPowder.rayleigh_step_s()).restitution;
        EXPECT_NEAR(returned / e, 1.0, 0.03) << "e " << e << ", " << speed << " m/s, " << (wall ? "wall" : "pair");
        // On steel the contact is stiffer and shorter (about 19 steps at 3 m/s): e 0.1 returns 0.963 there, so
        // steel is held to 3 % up to the speeds the scenes reach (a drop from the funnel's 80 mm: 1.25 m/s).
        if (wall && speed <= 1.25) {
          const double steel = impact(kPowder, e, true, speed, 0.08 * kPowder.rayleigh_step_s(), true).restitution;
          EXPECT_NEAR(steel / e, 1.0, 0.03) << "e " << e << ", " << speed << " m/s, steel wall";
        }
      }
}

namespace {

// The dashpot is fed a velocity extrapolated from two half steps, which is
// less stable than the half step's own. A sphere pressed on a floor (gravity
// 3000 m/s^2: an overlap past the 1 % the step rule assumes, so the resting
// contact sets the step) at e 0.02, the strongest damping a scene is likely
// to set, nudged at 0.1 mm/s: at the engine's step from the resting contact
// (safety factor 0.8) it comes to rest, and still at 2.0; at 4.0 (where the
// half step's own velocity would still be stable) it does not.
double resting_speed_m_s(double safety_factor) {
  const Material& m = kPowder;
  WorldSettings settings;
  settings.damping = 0.0;
  settings.gravity_m_s2 = {0, 0, -3000};
  World world(settings);
  const nlohmann::json p = {{"shear_modulus_pa", m.shear_modulus_pa}, {"poisson", m.poisson}, {"restitution", 0.02},
                            {"friction", 0.5}};
  world.assign(0, 1, world.add_model(ContactModelRegistry::instance().create("hertz_mindlin", p, "test")));
  world.spheres.add_sphere({0, 0, m.radius_m}, m.radius_m, m.density_kg_m3, 0);
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}, 1));
  world.refresh();
  for (int k = 0; k < 20000; ++k) world.step();
  world.settings().safety_factor = safety_factor;
  world.refresh();  // the step from the resting contact's stiffness
  world.spheres.set_velocity(0, {0, 0, 1e-4});  // a nudge
  for (int k = 0; k < 20000; ++k) world.step();
  return std::abs(world.spheres.vz[0]);
}

}  // namespace

TEST(HertzImpact3D, APressedSphereComesToRestAtTheEnginesStep) {
  EXPECT_LT(resting_speed_m_s(0.8), 1e-12);
  EXPECT_LT(resting_speed_m_s(2.0), 1e-12);
  EXPECT_FALSE(resting_speed_m_s(4.0) < 1e-3);
}
