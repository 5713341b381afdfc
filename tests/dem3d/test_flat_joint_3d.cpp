// The 3D flat joint against closed forms: its elements tile the disc (area
// pi R^2, second moments pi R^4 / 4, none across); an intact joint has a
// parallel bond's four stiffnesses, whatever the split; a pull breaks every
// element at the tensile strength in one step, each logged; bending breaks
// the far side first and leaves the rest bonded; a broken joint pressed
// together resists bending as the integral of its pressed face says, exactly
// while all of it is pressed; a joint broken and parted is a linear contact;
// a bonded fraction below 1 installs the other elements slit.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "../../dem/models3d/src/flat_joint_elements.hpp"
#include "bond_pair_harness.hpp"
#include "demcal/core/error.hpp"
#include "demcal/dem3d/linear_base.hpp"

using namespace demcal::dem3d;
namespace dem = demcal::dem;
using bond_test::Harness;
using bond_test::kRadius;
using json = nlohmann::json;

namespace {

constexpr double kJointModulus = 2e9, kJointKnKs = 2.5, kLambda = 0.8;
const double kJointRadius = kLambda * kRadius;
const double kArea = M_PI * kJointRadius * kJointRadius;
const double kInertia = 0.25 * M_PI * std::pow(kJointRadius, 4), kPolar = 2 * kInertia;
const double kJointKn = kJointModulus / (2 * kRadius), kJointKs = kJointKn / kJointKnKs;

json flat_joint_parameters(int radial, int circumferential, double tensile_pa = 1e12, double cohesion_pa = 1e12) {
  return {{"modulus_pa", 1e9},
          {"kn_ks", 2.0},
          {"friction", 0.5},
          {"joint_modulus_pa", kJointModulus},
          {"joint_kn_ks", kJointKnKs},
          {"radius_multiplier", kLambda},
          {"radial_elements", radial},
          {"circumferential_elements", circumferential},
          {"tensile_strength_pa", tensile_pa},
          {"cohesion_pa", cohesion_pa},
          {"friction_angle_deg", 30.0},
          {"joint_friction", 0.5}};
}

std::size_t column(const Harness& h, const std::string& name) {
  const auto names = h.model->state_columns();
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return c;
  ADD_FAILURE() << "no state column " << name;
  return 0;
}

const std::pair<int, int> kSplits[] = {{1, 1}, {1, 3}, {2, 4}, {3, 4}, {2, 6}};

}  // namespace

TEST(FlatJoint3D, ItsElementsTileTheDisc) {
  for (const auto& [radial, circumferential] : kSplits) {
    const auto elements = flat_joint::unit_disc_elements(radial, circumferential);
    ASSERT_EQ(elements.size(), static_cast<std::size_t>(radial * circumferential));
    double area = 0, first1 = 0, first2 = 0, second11 = 0, second22 = 0, second12 = 0;
    for (const auto& e : elements) {
      area += e.area, first1 += e.area * e.x1, first2 += e.area * e.x2;
      second11 += e.area * e.x1 * e.x1 + e.s11;
      second22 += e.area * e.x2 * e.x2 + e.s22;
      second12 += e.area * e.x1 * e.x2 + e.s12;
      double cells = 0, cells_u1 = 0, cells_u2 = 0;
      for (const auto& c : e.cells) cells += c.area, cells_u1 += c.area * c.u1, cells_u2 += c.area * c.u2;
      EXPECT_NEAR(cells, e.area, 1e-13);
      EXPECT_NEAR(cells_u1, 0.0, 1e-13) << "sub-cells centred on the element";
      EXPECT_NEAR(cells_u2, 0.0, 1e-13);
    }
    EXPECT_NEAR(area, M_PI, 1e-13) << radial << " x " << circumferential;
    EXPECT_NEAR(first1, 0.0, 1e-13);
    EXPECT_NEAR(first2, 0.0, 1e-13);
    EXPECT_NEAR(second11, M_PI / 4, 1e-13);
    EXPECT_NEAR(second22, M_PI / 4, 1e-13);
    EXPECT_NEAR(second12, 0.0, 1e-13);
  }
}

TEST(FlatJoint3D, AnElementsExtentBoundsALinearFunctionOverIt) {
  // Against a fine sampling of each element, in several directions: the
  // extent brackets every sample and is reached within the sampling's step.
  for (const auto& [radial, circumferential] : kSplits)
    for (const auto& e : flat_joint::unit_disc_elements(radial, circumferential))
      for (const auto& [a1, a2] : {std::pair{1.0, 0.0}, {0.3, -0.8}, {-1.0, 2.0}, {0.0, -1.0}}) {
        const auto [lo, hi] = e.extent(a1, a2);
        double sample_lo = INFINITY, sample_hi = -INFINITY;
        const int n = 400;
        for (int p = 0; p <= n; ++p)
          for (int q = 0; q <= n; ++q) {
            const double r = e.r_inner + (e.r_outer - e.r_inner) * p / n;
            const double a = e.angle_from + (e.angle_to - e.angle_from) * q / n;
            const double v = a1 * (r * std::cos(a) - e.x1) + a2 * (r * std::sin(a) - e.x2);
            sample_lo = std::min(sample_lo, v), sample_hi = std::max(sample_hi, v);
          }
        const double size = std::hypot(a1, a2), step = 2 * M_PI / n;
        EXPECT_LE(lo, sample_lo + 1e-12);
        EXPECT_GE(hi, sample_hi - 1e-12);
        EXPECT_GT(lo, sample_lo - step * size);
        EXPECT_LT(hi, sample_hi + step * size);
      }
}

TEST(FlatJoint3D, AnIntactJointHasAParallelBondsStiffnesses) {
  for (const auto& [radial, circumferential] : kSplits) {
    const json p = flat_joint_parameters(radial, circumferential);
    const std::string split = std::to_string(radial) + " x " + std::to_string(circumferential);
    {
      Harness h("flat_joint", p, {0, 0, 0}, {2 * kRadius, 0, 0});
      h.move(1000, {1e-3, 0, 0});
      h.step();
      const double stretch = 1000 * 1e-3 * h.dt, expected = kJointKn * kArea * stretch;
      EXPECT_NEAR(h.force().x, expected, 1e-9 * expected) << split << ": tension pulls i to j";
      EXPECT_NEAR(norm(h.moment_i()), 0.0, 1e-9 * expected * kRadius) << split;
    }
    for (const Vec3 v : {Vec3{0, 1e-3, 0}, Vec3{0, 0, -1e-3}}) {
      Harness h("flat_joint", p, {0, 0, 0}, {2 * kRadius, 0, 0});
      h.move(1000, v);
      h.step();
      const double expected = kJointKs * kArea * 1000 * h.dt * norm(v);
      EXPECT_NEAR(dot(h.force(), (1 / norm(v)) * v), expected, 1e-6 * expected) << split << ": shear";
    }
    for (const Vec3 axis : {Vec3{0, 0, 1}, Vec3{0, 1, 0}, Vec3{0, 0.6, -0.8}}) {
      // Bending: i and j turn opposite ways, so the contact points do not slide.
      Harness h("flat_joint", p, {0, 0, 0}, {2 * kRadius, 0, 0});
      h.move(1000, {}, -0.5 * axis, 0.5 * axis);
      h.step();
      const Vec3 expected = (kJointKn * kInertia * 1000 * h.dt) * axis;
      EXPECT_LT(norm(h.moment_i() - expected), 1e-9 * norm(expected)) << split << ": bending";
      EXPECT_LT(norm(h.force()), 1e-12 * norm(expected) / kRadius) << split;
    }
    {
      Harness h("flat_joint", p, {0, 0, 0}, {2 * kRadius, 0, 0});
      h.move(1000, {}, {-0.5, 0, 0}, {0.5, 0, 0});
      h.step();
      const double expected = kJointKs * kPolar * 1000 * h.dt;
      EXPECT_NEAR(h.moment_i().x, expected, 1e-9 * expected) << split << ": twisting";
    }
  }
}

TEST(FlatJoint3D, APullBreaksEveryElementAtTheTensileStrengthInOneStep) {
  const double strength = 2e6, speed = 1e-2;
  Harness h("flat_joint", flat_joint_parameters(2, 4, strength), {0, 0, 0}, {2 * kRadius, 0, 0});
  h.s.set_velocity(1, {speed, 0, 0});
  int steps = 0;
  while (h.bonded() && steps < 100000) {
    h.step();
    h.s.x[1] += speed * h.dt;
    ++steps;
  }
  ASSERT_FALSE(h.bonded());
  // sigma = k_n gap passes 2 MPa at a stretch of 2e6 / k_n: the step after.
  EXPECT_NEAR(steps * speed * h.dt, strength / kJointKn, 1.01 * speed * h.dt);
  EXPECT_EQ(tension_breaks(h.set.flags[0]), 8u) << "each element's break is a crack";
  EXPECT_EQ(shear_breaks(h.set.flags[0]), 0u);
  EXPECT_EQ(norm(h.force()), 0.0) << "a broken, parted joint carries nothing";
}

TEST(FlatJoint3D, BendingBreaksTheOpeningSideFirstAndLeavesTheRestBonded) {
  // One ring of 4 quarter-disc sectors. The joint's frame for a normal along
  // x is t1 = y, t2 = z: bending about z opens the -y side, where sectors 2
  // and 3 meet, and presses the +y side.
  const double strength = 2e6;
  Harness h("flat_joint", flat_joint_parameters(1, 4, strength), {0, 0, 0}, {2 * kRadius, 0, 0});
  const std::size_t bonded1 = column(h, "element1_bonded");
  auto bonded = [&](int e) { return h.block().column[bonded1 + 6 * static_cast<std::size_t>(e)][0] != 0.0; };
  h.s.set_spin(0, {0, 0, -0.5}), h.s.set_spin(1, {0, 0, 0.5});
  int steps = 0;
  while (bonded(0) && bonded(1) && bonded(2) && bonded(3) && steps < 1000000) h.step(), ++steps;
  ASSERT_LT(steps, 1000000);
  EXPECT_TRUE(bonded(0) && bonded(3)) << "the pressed side holds";
  EXPECT_FALSE(bonded(1) || bonded(2)) << "the opening side's two sectors break together";
  EXPECT_TRUE(h.bonded()) << "partial damage: the joint holds by its other elements";
  EXPECT_EQ(tension_breaks(h.set.flags[0]), 2u);
  // A quarter disc's centroid lies 4 R / (3 pi) from each of its straight
  // edges: the gap there is that times theta, and sigma = k_n gap passes the
  // strength on the step after.
  const double theta_at_break = strength / (kJointKn * 4 * kJointRadius / (3 * M_PI));
  EXPECT_NEAR(steps * h.dt, theta_at_break, 1.01 * h.dt);
}

// The pressed segment u1 > d of a disc of radius R under a gap d - u1 (per
// unit of theta): its force integral of the gap, and its moment integral of
// the gap times u1, with chord 2 sqrt(R^2 - u^2).
struct Segment {
  double gap_area, gap_moment;
};
Segment pressed_segment(double d, double R) {
  const auto root = [&](double u) { return std::sqrt(std::max(R * R - u * u, 0.0)); };
  const auto i0 = [&](double u) { return u * root(u) + R * R * std::asin(u / R); };
  const auto i1 = [&](double u) { return -2.0 / 3.0 * std::pow(R * R - u * u, 1.5); };
  const auto i2 = [&](double u) { return 0.25 * (u * (2 * u * u - R * R) * root(u) + std::pow(R, 4) * std::asin(u / R)); };
  const double area = i0(R) - i0(d), first = i1(R) - i1(d), second = i2(R) - i2(d);
  return {d * area - first, d * first - second};
}

// A joint pressed by 2e-8 m, then sheared until every element breaks in
// shear (cohesion 1 kPa): broken, but pressed all over its face.
Harness broken_pressed_joint(int radial, int circumferential) {
  Harness h("flat_joint", flat_joint_parameters(radial, circumferential, 1e12, 1e3), {0, 0, 0}, {2 * kRadius, 0, 0});
  h.move(2000, {-1e-3, 0, 0});
  h.move(10000, {0, 0, 1e-3});
  return h;
}

TEST(FlatJoint3D, ABrokenJointPressedTogetherResistsBendingByItsPressedFace) {
  // Bent about z (t2): while all of the face is pressed, the moment on i is
  // k_n I theta and the normal force k_n A gap; once the -y side opens, the
  // pressed segment's integrals, within 1.5e-3 of the disc's force (k_n A R
  // theta) and 6e-3 of its moment (k_n I theta), as the sub-cells promise.
  for (const auto& [radial, circumferential] : kSplits) {
    const std::string split = std::to_string(radial) + " x " + std::to_string(circumferential);
    {
      Harness h = broken_pressed_joint(radial, circumferential);
      ASSERT_FALSE(h.bonded()) << split;
      const Vec3 f = h.force();
      EXPECT_NEAR(std::hypot(f.y, f.z) / std::abs(f.x), 0.5, 1e-3) << split << ": broken elements slide at mu F_n";
    }
    const double w = 1.0;
    for (const int bend_steps : {1000, 2000, 3000, 10000, 40000}) {
      Harness h = broken_pressed_joint(radial, circumferential);
      const double gap = h.block().column[column(h, "element1_gap_m")][0];
      ASSERT_NEAR(gap, -2e-8, 1e-11);
      h.move(bend_steps, {}, {0, 0, -0.5 * w}, {0, 0, 0.5 * w});
      h.s.set_spin(0, {0, 0, -0.5 * w}), h.s.set_spin(1, {0, 0, 0.5 * w});
      h.step();
      const double theta = (bend_steps + 1) * w * h.dt;
      // Along t1 = y the gap is gap - theta u1: pressed where u1 > gap / theta.
      const double d = gap / theta;
      double force_n = 0, moment_nm = 0;
      if (d <= -kJointRadius) {
        force_n = kJointKn * kArea * gap, moment_nm = kJointKn * kInertia * theta;
      } else {
        const Segment seg = pressed_segment(d, kJointRadius);
        force_n = kJointKn * theta * seg.gap_area, moment_nm = -kJointKn * theta * seg.gap_moment;
      }
      EXPECT_NEAR(h.force().x, force_n, 1.5e-3 * kJointKn * kArea * kJointRadius * theta)
          << split << " at theta " << theta;
      EXPECT_NEAR(h.moment_i().z, moment_nm, 6e-3 * kJointKn * kInertia * theta) << split << " at theta " << theta;
    }
  }
}

TEST(FlatJoint3D, AJointBrokenAndPartedIsALinearContact) {
  Harness h("flat_joint", flat_joint_parameters(1, 3, 1e3), {0, 0, 0}, {2 * kRadius, 0, 0});
  const std::size_t joint = column(h, "joint");
  h.move(3000, {1e-3, 0, 0});
  EXPECT_EQ(h.block().column[joint][0], 0.0) << "broken everywhere and open: no joint left";
  // Pushed to an overlap: the linear law, kn = pi r^2 E / (R_i + R_j).
  h.move(5000, {-1e-3, 0, 0});
  h.step();
  const double overlap = 2 * kRadius - h.s.x[1];
  ASSERT_GT(overlap, 0.0);
  const double kn = M_PI * kRadius * kRadius * 1e9 / (2 * kRadius);
  EXPECT_NEAR(h.force().x, -kn * overlap, 1e-9 * kn * overlap);
}

TEST(FlatJoint3D, RefusesASplitItCannotMake) {
  for (const auto& [key, value] : {std::pair<const char*, double>{"radial_elements", 5},
                                   {"circumferential_elements", 9},
                                   {"circumferential_elements", 2.5},
                                   {"circumferential_elements", 7},  // 14 elements with radial 2
                                   {"friction_angle_deg", 90}}) {
    json p = flat_joint_parameters(2, 3);
    p[key] = value;
    EXPECT_THROW(ContactModelRegistry::instance().create("flat_joint", p, "scene.json"), demcal::Error) << key;
  }
  json p = flat_joint_parameters(1, 3);
  p["elements"] = 2;  // the 2D key: the 3D disc is split two ways
  EXPECT_THROW(ContactModelRegistry::instance().create("flat_joint", p, "scene.json"), demcal::Error);
}

TEST(FlatJoint3D, ABondedFractionInstallsTheRestOfTheElementsSlit) {
  // 2,000 joints of 2 x 4 elements at phi_B 0.6: the bonded share within 5
  // binomial deviations (0.02), the strengths drawn as at phi_B 1, and a joint
  // with no bonded element left a plain contact.
  const auto install = [](double fraction, std::size_t pairs, std::vector<bool>& installed) {
    json p = flat_joint_parameters(2, 4, 2e6, 4e6);
    p["tensile_strength_std_pa"] = 5e5;
    p["bonded_fraction"] = fraction;
    auto model = ContactModelRegistry::instance().create("flat_joint", p, "test");
    auto set = std::make_unique<dem::ContactSet>();
    set->set_layout({model->state_columns().size()});
    set->assign_blocks({pairs});
    dem::PairBlock b = set->block(0);
    PairInfo info;
    info.radius_i = info.radius_j = kRadius;
    installed.assign(pairs, false);
    for (std::size_t k = 0; k < pairs; ++k) {
      model->initialise(b, k, info);
      demcal::Rng rng(k, 2);
      installed[k] = model->install_bond(b, k, info, rng);
    }
    return std::make_pair(std::move(model), std::move(set));
  };
  std::vector<bool> all, some;
  const auto [full_model, full] = install(1.0, 2000, all);
  const auto [part_model, part] = install(0.6, 2000, some);
  const std::size_t first = kLinearColumns + 10;  // element 1's columns: gap, shear 1, shear 2, bonded, tensile, cohesion
  std::size_t bonded = 0, joints = 0;
  for (std::size_t k = 0; k < 2000; ++k) {
    EXPECT_TRUE(all[k]);
    joints += some[k];
    for (std::size_t e = 0; e < 8; ++e) {
      const std::size_t c = first + 6 * e;
      bonded += part->block(0).column[c + 3][k] != 0.0;
      EXPECT_EQ(part->block(0).column[c + 4][k], full->block(0).column[c + 4][k]) << "strengths do not move with phi_B";
    }
  }
  EXPECT_NEAR(static_cast<double>(bonded) / 16000, 0.6, 0.02);
  EXPECT_NEAR(static_cast<double>(joints) / 2000, 1 - std::pow(0.4, 8), 0.002);
  std::vector<bool> none;
  const auto [slit_model, slit] = install(0.0, 10, none);
  for (std::size_t k = 0; k < 10; ++k) {
    EXPECT_FALSE(none[k]);
    EXPECT_EQ(slit->block(0).column[kLinearColumns][k], 0.0) << "no joint";
    EXPECT_EQ(slit->block(0).flags[k] & dem::kBonded, 0u);
  }
}
