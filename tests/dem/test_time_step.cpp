// The critical time step against the largest eigenfrequency of small bonded
// clusters, computed here independently: the stiffness matrix of every bond
// and contact spring (normal, shear at the contact point, bending), the mass
// matrix of the disks, and omega_max from the generalised eigenproblem.
// Central differences are stable while dt omega_max < 2; the engine's step
// (safety factor 0.8 on its per-disk estimate) must stay below that for any
// stiffness ratio, including bond kn/ks < 1 where the bond's shear spring is
// the stiffest.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/world.hpp"
#include "bonded_bodies.hpp"

using namespace demcal::dem;

namespace {

constexpr double kR = 1e-3, kRho = 2650, kT = 1.0, kModulus = 1e9;

struct Cluster {
  std::vector<std::pair<double, double>> centres;
  std::vector<std::pair<int, int>> pairs;
};

Cluster pair_cluster() { return {{{0, 0}, {2 * kR, 0}}, {{0, 1}}}; }
Cluster triangle() { return {{{0, 0}, {2 * kR, 0}, {kR, std::sqrt(3.0) * kR}}, {{0, 1}, {1, 2}, {0, 2}}}; }
Cluster hexagon() {
  Cluster c;
  c.centres.push_back({0, 0});
  for (int k = 0; k < 6; ++k) c.centres.push_back({2 * kR * std::cos(k * M_PI / 3), 2 * kR * std::sin(k * M_PI / 3)});
  for (int k = 1; k <= 6; ++k) {
    c.pairs.push_back({0, k});
    c.pairs.push_back({k, k % 6 + 1});
  }
  return c;
}

// omega_max of equal disks joined at every pair by a linear contact (kn, ks)
// in parallel with a parallel bond of radius R (lambda = 1): normal spring
// kn + kn_b A, shear spring ks + ks_b A at the contact point, bending kn_b I.
double largest_omega(const Cluster& cluster, double kn_ks, double bond_kn_ks) {
  const int n = static_cast<int>(cluster.centres.size());
  const double kn = 2 * kR * kT * kModulus / (2 * kR), ks = kn / kn_ks;
  const double kbn = kModulus / (2 * kR), kbs = kbn / bond_kn_ks, area = 2 * kR * kT, inertia = 2.0 / 3.0 * kR * kR * kR * kT;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  auto add = [&](const Eigen::VectorXd& b, double k) { K += k * b * b.transpose(); };
  for (const auto& [i, j] : cluster.pairs) {
    const double dx = cluster.centres[j].first - cluster.centres[i].first;
    const double dy = cluster.centres[j].second - cluster.centres[i].second;
    const double l = std::hypot(dx, dy), nx = dx / l, ny = dy / l, tx = -ny, ty = nx;
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(3 * n), shear = normal, bend = normal;
    normal(3 * j) = nx, normal(3 * j + 1) = ny, normal(3 * i) = -nx, normal(3 * i + 1) = -ny;
    // Relative sliding at the contact point: (v_j - v_i) . t - (R w_i + R w_j).
    shear(3 * j) = tx, shear(3 * j + 1) = ty, shear(3 * i) = -tx, shear(3 * i + 1) = -ty;
    shear(3 * i + 2) = -kR, shear(3 * j + 2) = -kR;
    bend(3 * j + 2) = 1, bend(3 * i + 2) = -1;
    add(normal, kn + kbn * area);
    add(shear, ks + kbs * area);
    add(bend, kbn * inertia);
  }
  const double m = kRho * M_PI * kR * kR * kT, moment_of_inertia = 0.5 * m * kR * kR;
  Eigen::VectorXd inverse_sqrt_mass(3 * n);
  for (int i = 0; i < n; ++i)
    inverse_sqrt_mass.segment(3 * i, 3) << 1 / std::sqrt(m), 1 / std::sqrt(m), 1 / std::sqrt(moment_of_inertia);
  const Eigen::MatrixXd A = inverse_sqrt_mass.asDiagonal() * K * inverse_sqrt_mass.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(A, Eigen::EigenvaluesOnly);
  return std::sqrt(solver.eigenvalues().maxCoeff());
}

double engine_step(const Cluster& cluster, double kn_ks, double bond_kn_ks) {
  World world;
  world.assign(0, 0, world.add_model(demcal::dem::testing::unbreakable_parallel_bond(kModulus, kn_ks, kModulus, bond_kn_ks)));
  for (const auto& [x, y] : cluster.centres) world.bodies.add_disk(x, y, kR, kRho, kT, 0);
  EXPECT_EQ(world.install_bonds(1e-9, 1), cluster.pairs.size());
  return world.dt_s();
}

}  // namespace

TEST(TimeStep, StaysBelowTheStabilityLimitOfBondedClusters) {
  struct Case {
    const char* name;
    Cluster cluster;
  };
  const Case cases[] = {{"pair", pair_cluster()}, {"triangle", triangle()}, {"hexagon of 7", hexagon()}};
  for (const Case& c : cases)
    for (double kn_ks : {0.5, 1.0, 2.5, 4.0})
      for (double bond_kn_ks : {0.5, 1.0, 2.5}) {
        const double product = engine_step(c.cluster, kn_ks, bond_kn_ks) * largest_omega(c.cluster, kn_ks, bond_kn_ks);
        // Below 2 for stability, with room for the safety factor's intent
        // (0.8 of the critical step); above 0.5 so the estimate is not wasteful.
        EXPECT_LT(product, 0.8 * 2.0) << c.name << ", kn/ks " << kn_ks << ", bond kn/ks " << bond_kn_ks;
        EXPECT_GT(product, 0.5) << c.name << ", kn/ks " << kn_ks << ", bond kn/ks " << bond_kn_ks;
      }
}
