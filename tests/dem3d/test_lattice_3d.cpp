// The elastic constants of a face-centred cubic lattice of bonded spheres
// against their closed form. With nearest neighbours joined by a normal spring
// kn and a shear spring ks (a contact bond, which carries tension), a
// homogeneous strain is an equilibrium (the lattice is centrosymmetric and
// cubic, so neither a net force nor a net moment acts on a sphere), and the
// lattice sums of sigma = (1/V) sum f (x) d give, with d = 2R the distance
// between neighbours and V = 4 sqrt(2) R^3 per sphere:
//   C11 = sqrt(2) (kn + ks) / d,  C12 = (kn - ks) / (sqrt(2) d),  C44 = (kn + ks) / (sqrt(2) d).
// The world moves the spheres: their masses are so large that the contact
// forces leave the velocities of a homogeneous strain rate unchanged, so every
// contact feels the affine motion through the engine's own geometry,
// neighbour list, shear turning and integration.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/world.hpp"

using namespace demcal::dem3d;

namespace {

constexpr double kR = 1e-3, kKn = 1e6, kKs = 4e5;
constexpr int kCells = 6;

using Tensor = std::array<std::array<double, 3>, 3>;

// The stress of the interior spheres (a full shell of 12 neighbours) after
// straining the lattice at `rate` (1/s, symmetric) for `steps` steps.
Tensor interior_stress(const Tensor& rate, int steps, double dt) {
  WorldSettings settings;
  settings.damping = 0.0;
  settings.fixed_dt_s = dt;
  World w(settings);
  const nlohmann::json p = {{"kn_n_m", kKn}, {"ks_n_m", kKs}, {"friction", 0.5},
                            {"tensile_strength_pa", 1e20}, {"shear_strength_pa", 1e20}};
  w.assign(0, 0, w.add_model(ContactModelRegistry::instance().create("contact_bond", p, "lattice")));
  const double a = 2 * std::sqrt(2.0) * kR;
  const Vec3 basis[4] = {{0, 0, 0}, {0.5 * a, 0.5 * a, 0}, {0.5 * a, 0, 0.5 * a}, {0, 0.5 * a, 0.5 * a}};
  for (int x = 0; x < kCells; ++x)
    for (int y = 0; y < kCells; ++y)
      for (int z = 0; z < kCells; ++z)
        for (const Vec3& b : basis) w.spheres.add_sphere(Vec3{x * a, y * a, z * a} + b, kR, 1e20, 0);
  const std::size_t bonds = w.install_bonds(1e-9 * kR, 1);
  EXPECT_EQ(bonds, w.pairs().size()) << "every nearest pair bonded, no other pair";
  const Vec3 centre{0.5 * kCells * a, 0.5 * kCells * a, 0.5 * kCells * a};
  for (std::size_t i = 0; i < w.spheres.size(); ++i) {
    const Vec3 x = w.spheres.position(i) - centre;
    w.spheres.set_velocity(i, {rate[0][0] * x.x + rate[0][1] * x.y + rate[0][2] * x.z,
                               rate[1][0] * x.x + rate[1][1] * x.y + rate[1][2] * x.z,
                               rate[2][0] * x.x + rate[2][1] * x.y + rate[2][2] * x.z});
  }
  w.run(static_cast<std::uint64_t>(steps));
  // Per interior sphere: (1 / 2V) sum over its 12 pairs of f (x) d, f the force on it.
  const double volume = 4 * std::sqrt(2.0) * kR * kR * kR;
  Tensor sigma{};
  std::vector<int> pairs_of(w.spheres.size(), 0);
  const auto& set = w.pairs();
  for (std::size_t k = 0; k < set.size(); ++k) ++pairs_of[set.i[k]], ++pairs_of[set.j[k]];
  std::size_t interior = 0;
  for (int n : pairs_of) interior += n == 12;
  EXPECT_GT(interior, 100u);
  for (std::size_t k = 0; k < set.size(); ++k) {
    const auto i = static_cast<std::size_t>(set.i[k]), j = static_cast<std::size_t>(set.j[k]);
    const Vec3 d = w.spheres.position(j) - w.spheres.position(i);
    const double distance = norm(d);
    const Vec3 n = (1 / distance) * d;
    const double fn = w.pair_state(k, "kn_n_m") * (2 * kR - distance - w.pair_state(k, "reference_overlap_m"));
    const Vec3 fs{w.pair_state(k, "shear_force_x_n"), w.pair_state(k, "shear_force_y_n"),
                  w.pair_state(k, "shear_force_z_n")};
    const Vec3 on_i = fs - fn * n;  // and -on_i on j, whose d is -d: the same f (x) d
    const double f[3] = {on_i.x, on_i.y, on_i.z}, dd[3] = {d.x, d.y, d.z};
    const double weight = 0.5 * ((pairs_of[i] == 12) + (pairs_of[j] == 12)) / (volume * static_cast<double>(interior));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) sigma[r][c] += weight * f[r] * dd[c];
  }
  return sigma;
}

}  // namespace

TEST(Lattice3D, FaceCentredCubicElasticConstantsMatchTheClosedForm) {
  const double d = 2 * kR;
  const double c11 = std::sqrt(2.0) * (kKn + kKs) / d, c12 = (kKn - kKs) / (std::sqrt(2.0) * d),
               c44 = (kKn + kKs) / (std::sqrt(2.0) * d);
  const int steps = 200;
  const double dt = 1e-6, rate = 0.5;  // a strain of 1e-4
  const double e = rate * steps * dt;
  {
    const Tensor s = interior_stress({{{rate, 0, 0}, {0, 0, 0}, {0, 0, 0}}}, steps, dt);
    EXPECT_NEAR(s[0][0] / e, c11, 2e-3 * c11);
    EXPECT_NEAR(s[1][1] / e, c12, 2e-3 * c11);
    EXPECT_NEAR(s[2][2] / e, c12, 2e-3 * c11);
    EXPECT_NEAR(s[0][1] / e, 0.0, 2e-3 * c11);
  }
  {
    // A shear strain eps_xy = eps_yx = e: sigma_xy = 2 C44 e, no normal stress.
    const Tensor s = interior_stress({{{0, rate, 0}, {rate, 0, 0}, {0, 0, 0}}}, steps, dt);
    EXPECT_NEAR(s[0][1] / e, 2 * c44, 2e-3 * c11);
    EXPECT_NEAR(s[1][0] / e, 2 * c44, 2e-3 * c11);
    EXPECT_NEAR(s[0][0] / e, 0.0, 2e-3 * c11);
    EXPECT_NEAR(s[2][2] / e, 0.0, 2e-3 * c11);
  }
}
