// The 3D powder contact models against closed forms: JKR's pull-off force
// -1.5 pi w R*, its hysteresis (a contact forms on touch and holds to the
// separation delta_c), LIGGGHTS' sjkr attraction k A over the crossing circle
// of two spheres; rolling resistance type A stopping a sphere spinning on a
// floor at mu_r R F_n / I and holding it still, type C (which resists rolling,
// not twisting) slowing a rolling sphere at mu_r g / 1.4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem/jkr_curve.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;
namespace dem = demcal::dem;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2500, kShearModulus = 1e7, kPoisson = 0.25;

nlohmann::json hertz_keys(nlohmann::json extra) {
  nlohmann::json p = {{"shear_modulus_pa", kShearModulus}, {"poisson", kPoisson}, {"restitution", 0.5},
                      {"friction", 0.5}};
  if (extra.is_object()) p.update(extra);
  return p;
}

double effective_modulus() {
  const double e = 2 * kShearModulus * (1 + kPoisson);
  return 1.0 / (2 * (1 - kPoisson * kPoisson) / e);
}

// One pair of equal spheres at rest, centres `distance_m` apart along x: the
// model's force on i (the pair's state carried between calls).
struct Pair {
  std::unique_ptr<ContactModel> model;
  Spheres s;
  dem::ContactSet set;
  std::vector<double> f = std::vector<double>(9, 0.0);

  explicit Pair(const std::string& name, const nlohmann::json& parameters)
      : model(ContactModelRegistry::instance().create(name, parameters, "test")) {
    s.add_sphere({0, 0, 0}, kRadius, kDensity, 0);
    s.add_sphere({2 * kRadius, 0, 0}, kRadius, kDensity, 0);
    set.set_layout({model->state_columns().size()});
    set.assign_blocks({1});
    set.i[0] = 0, set.j[0] = 1;
    dem::PairBlock block = set.block(0);
    for (std::size_t c = 0; c < model->state_columns().size(); ++c) block.column[c][0] = 0;
    PairInfo info;
    info.radius_i = info.radius_j = kRadius;
    info.mass_i_kg = s.mass[0], info.mass_j_kg = s.mass[1];
    model->initialise(block, 0, info);
  }
  // The normal force on j along +x (> 0 repulsive) at centre distance d.
  double normal_force(double distance_m) {
    s.x[1] = distance_m;
    dem::PairBlock block = set.block(0);
    const PairForces out{&f[0], &f[1], &f[2], &f[3], &f[5], &f[7]};
    model->sphere_forces(block, s, out, {1e-7, 0});
    return f[0] * -1.0;  // the force on i is -x when repulsive
  }
  bool touching() const { return (set.flags[0] & dem::kTouching) != 0; }
};

}  // namespace

TEST(Jkr3D, PullOffIsOneAndAHalfPiWRStar) {
  const double w = 0.05, radius_eff = kRadius / 2;
  Pair pair("jkr", hertz_keys({{"work_of_adhesion_j_m2", w}}));
  const dem::JkrCurve curve(effective_modulus(), w);
  const double limit = curve.separation_limit(radius_eff);
  // From an overlap of 1e-6 m out to the end of the curve, in small steps.
  double least = 0;
  ASSERT_GT(pair.normal_force(2 * kRadius - 1e-6), 0.0);
  for (double overlap = 1e-6; overlap > -1.2 * limit; overlap -= 1e-10)
    least = std::min(least, pair.normal_force(2 * kRadius - overlap));
  EXPECT_NEAR(least, -1.5 * M_PI * w * radius_eff, 1e-3 * 1.5 * M_PI * w * radius_eff);
}

TEST(Jkr3D, ContactFormsOnTouchAndHoldsToTheSeparationLimit) {
  const double w = 0.05, radius_eff = kRadius / 2;
  Pair pair("jkr", hertz_keys({{"work_of_adhesion_j_m2", w}}));
  const double limit = dem::JkrCurve(effective_modulus(), w).separation_limit(radius_eff);
  ASSERT_GT(limit, 0.0);
  // Approaching across a gap of half the limit: no contact, no force.
  EXPECT_EQ(pair.normal_force(2 * kRadius + 0.5 * limit), 0.0);
  EXPECT_FALSE(pair.touching());
  // Touching: the contact forms; pulled back to that gap, it holds and pulls.
  pair.normal_force(2 * kRadius - 1e-7);
  EXPECT_TRUE(pair.touching());
  EXPECT_LT(pair.normal_force(2 * kRadius + 0.5 * limit), 0.0);
  EXPECT_TRUE(pair.touching());
  EXPECT_LT(pair.normal_force(2 * kRadius + 0.99 * limit), 0.0);
  // Past the end of the curve it lets go.
  EXPECT_EQ(pair.normal_force(2 * kRadius + 1.01 * limit), 0.0);
  EXPECT_FALSE(pair.touching());
}

TEST(Jkr3D, WithoutAdhesionItIsHertzMindlin) {
  Pair jkr("jkr", hertz_keys({{"work_of_adhesion_j_m2", 0.0}}));
  Pair hertz("hertz_mindlin", hertz_keys({}));
  for (double overlap : {1e-7, 1e-6, 1e-5}) {
    const double a = jkr.normal_force(2 * kRadius - overlap), b = hertz.normal_force(2 * kRadius - overlap);
    EXPECT_NEAR(a, b, 1e-12 * b);
    // 4/3 E* sqrt(R*) delta^(3/2)
    EXPECT_NEAR(b, 4.0 / 3.0 * effective_modulus() * std::sqrt(kRadius / 2) * std::pow(overlap, 1.5), 1e-9 * b);
  }
}

TEST(Sjkr3D, AttractionIsEnergyDensityTimesTheCrossingCircle) {
  const double k = 2e5;  // J/m^3
  Pair sjkr("sjkr", hertz_keys({{"cohesion_energy_density_j_m3", k}}));
  Pair hertz("hertz_mindlin", hertz_keys({}));
  for (double overlap : {1e-7, 1e-6, 1e-5}) {
    const double d = 2 * kRadius - overlap;
    // Equal spheres: the circle's radius^2 is R^2 - (d/2)^2.
    const double area = M_PI * (kRadius * kRadius - 0.25 * d * d);
    EXPECT_NEAR(sjkr.normal_force(d), hertz.normal_force(d) - k * area, 1e-9 * k * area);
  }
  // No force across a gap.
  EXPECT_EQ(sjkr.normal_force(2 * kRadius + 1e-7), 0.0);
}

namespace {

// A sphere settled on a floor under gravity (the model's own, restitution
// 0.5), then given a spin `spin` and a velocity `velocity`; returns the world.
World sphere_on_floor(const nlohmann::json& parameters, Vec3 spin, Vec3 velocity) {
  WorldSettings settings;
  settings.damping = 0.0;
  settings.gravity_m_s2 = {0, 0, -9.81};
  World world(settings);
  const auto model = world.add_model(ContactModelRegistry::instance().create("hertz_mindlin", parameters, "test"));
  world.assign(0, 1, model);
  world.spheres.add_sphere({0, 0, kRadius}, kRadius, kDensity, 0);
  world.walls.push_back(make_plane({0, 0, 0}, {0, 0, 1}, 1));
  world.refresh();
  const double dt = world.dt_s();
  for (int k = 0; k * dt < 0.05; ++k) world.step();  // settled: the dashpot takes the bounce out
  world.spheres.set_spin(0, spin);
  world.spheres.set_velocity(0, velocity);
  return world;
}

}  // namespace

TEST(Rolling3D, TypeAStopsASpinningSphereAndHoldsIt) {
  const double mu_r = 0.1, spin0 = 20.0;
  World world = sphere_on_floor(hertz_keys({{"rolling_friction_cdt", mu_r}}), {0, 0, spin0}, {});
  // Spinning about the normal, friction gives no couple: only type A slows it,
  // at mu_r R m g / I = 2.5 mu_r g / R.
  const double deceleration = 2.5 * mu_r * 9.81 / kRadius, stop_s = spin0 / deceleration;
  const double t0 = world.time_s();
  while (world.spheres.wz[0] > 0 && world.time_s() - t0 < 2 * stop_s) world.step();
  EXPECT_NEAR(world.time_s() - t0, stop_s, 0.02 * stop_s);
  for (int k = 0; k < 2000; ++k) world.step();
  EXPECT_EQ(world.spheres.wx[0], 0.0);
  EXPECT_EQ(world.spheres.wy[0], 0.0);
  EXPECT_EQ(world.spheres.wz[0], 0.0);
}

TEST(Rolling3D, TypeCResistsRollingNotTwisting) {
  const double mu_r = 0.1;
  // Twisting: the spin is along the normal, nothing resists it.
  World twisting = sphere_on_floor(hertz_keys({{"rolling_friction_epsd", mu_r}}), {0, 0, 20.0}, {});
  for (int k = 0; k < 2000; ++k) twisting.step();
  EXPECT_NEAR(twisting.spheres.wz[0], 20.0, 1e-9);
  // Rolling along x at 0.1 m/s: once the couple is fully mobilised (about
  // 10 ms here), mu_r R F_n slows it at mu_r g / 1.4 (the sphere's inertia
  // about its contact point), measured from 30 to 90 ms.
  const double v0 = 0.1;
  World rolling = sphere_on_floor(hertz_keys({{"rolling_friction_epsd", mu_r}}), {0, v0 / kRadius, 0}, {v0, 0, 0});
  const double t0 = rolling.time_s();
  while (rolling.time_s() - t0 < 0.03) rolling.step();
  const double t1 = rolling.time_s(), v1 = rolling.spheres.vx[0];
  while (rolling.time_s() - t0 < 0.09) rolling.step();
  const double deceleration = (v1 - rolling.spheres.vx[0]) / (rolling.time_s() - t1);
  EXPECT_NEAR(deceleration, mu_r * 9.81 / 1.4, 0.02 * mu_r * 9.81 / 1.4);
}
