// Flat joint in 3D (Potyondy 2012; PFC3D's flatjoint): a bonded pair is
// joined across a flat disc of radius R_j = lambda min(R_i, R_j) split into
// rings and sectors (flat_joint_elements.hpp). Each element is bonded
// (tensile strength, Mohr-Coulomb shear strength c - sigma tan(phi_b)) or,
// once broken, frictional (no tension, |F_s| <= mu F_n); a joint breaks
// element by element, and a broken face stays flat, so where it is pressed
// it still resists rotation. That is what reaches rock's UCS / tensile
// strength ratios of 10-20, where a parallel bond gives about 4.
//   parameters: the linear model's (for pairs that meet during the test),
//               "joint_modulus_pa", "joint_kn_ks" (kn = E_j / (R_i + R_j),
//               ks = kn / (kn/ks)_j per area), "radius_multiplier" (lambda,
//               default 1), "radial_elements" (1-4, default 1),
//               "circumferential_elements" (1-8, default 3; 12 elements at most),
//               "tensile_strength_pa", "tensile_strength_std_pa" (default 0),
//               "cohesion_pa", "cohesion_std_pa" (default 0),
//               "friction_angle_deg" (phi_b of bonded elements),
//               "joint_friction" (mu of broken elements), "bonded_fraction"
//               (phi_B, default 1: the share of elements installed bonded;
//               the rest are installed slit, unbonded faces in contact)
// Kinematics, incremental from installation (the joint is force-free
// there), in the joint's own frame (t1, t2, n), which turns with the contact
// plane as a shear force does: with w the spin of j relative to i and x_e
// an element's centroid, its gap grows by (v_n + (w x x_e).n) dt and its
// shear force (on i) by k_s A_e (v_t + w_n n x x_e) dt. A bonded element
// carries F_n = k_n A_e gap at its centroid, and about it the moments of its
// own section: bending k_n S_e theta_b and twisting k_s J_e theta_t, with
// theta the relative rotation since installation, so an intact joint has a
// parallel bond's four stiffnesses exactly (sum of A_e x_e x_e + S_e = pi
// R_j^4 / 4 per axis). Its average stresses sigma = k_n gap (tension > 0)
// and tau = |F_s| / A_e are checked against its strengths, broken strictly
// beyond them (a zero strength breaks an element at its first load, never at
// rest). A broken element pushes only where its faces overlap: the gap
// varies as gap + (theta_b x u).n across it, and an element pressed over
// part of its face is summed over sub-cells. Each element break is
// a crack in the log; the pair stays a joint (held in the neighbour list)
// while an element is bonded, and a fully broken joint whose faces have
// parted everywhere becomes a linear contact at once, as a pair that meets
// during the test is.
//   state: the linear columns, then the joint's (stiffnesses per area,
//   radius, frame t1, theta_b in the frame, theta_t) and per element gap,
//   shear force in the frame, bonded, and its drawn strengths.
#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/linear_base.hpp"
#include "flat_joint_elements.hpp"

namespace demcal::dem3d {
namespace {

// Each element keeps 6 state columns: 12 elements at most.
constexpr int kMaxRadial = 4, kMaxCircumferential = 8, kMaxElements = 12;

enum JointColumn : std::size_t {
  kJoint = kLinearColumns,  // 1 for an installed joint, 0 for a linear contact
  kJointKn,                 // normal stiffness per area, Pa/m
  kJointKs,                 // shear stiffness per area, Pa/m
  kJointRadius,             // R_j, m
  kFrameX,                  // t1, a unit vector in the joint's plane (0: not yet set)
  kFrameY,
  kFrameZ,
  kBend1,                   // relative bending rotation along t1, t2, rad
  kBend2,
  kTwist,                   // relative rotation about n, rad
  kElementColumns           // then per element: gap, shear force along t1, t2, bonded, strengths
};
enum ElementColumn : std::size_t { kGap = 0, kShear1, kShear2, kBondedElement, kTensile, kCohesion, kPerElement };

std::size_t column_of(std::size_t e, ElementColumn column) { return kElementColumns + e * kPerElement + column; }

int whole_number(const nlohmann::json& p, const char* key, int fallback, int most, const std::string& where) {
  if (!p.contains(key)) return fallback;
  const double n = dem::positive(p, key, where);
  if (n != std::floor(n) || n > most)
    throw Error(where + ": \"" + key + "\" must be a whole number from 1 to " + std::to_string(most));
  return static_cast<int>(n);
}

// A frame vector in the plane of normal n, fixed by n alone (so by the
// pair's geometry, whatever the storage order): the world axis most across n.
Vec3 first_frame_vector(Vec3 n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const Vec3 e = ax <= ay && ax <= az ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  const Vec3 t = e - dot(e, n) * n;
  return (1.0 / norm(t)) * t;
}

class FlatJointModel : public LinearBase {
 public:
  FlatJointModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        joint_modulus_pa_(dem::positive(p, "joint_modulus_pa", where)),
        joint_kn_ks_(dem::positive(p, "joint_kn_ks", where)),
        lambda_(p.contains("radius_multiplier") ? dem::positive(p, "radius_multiplier", where) : 1.0),
        sigma_c_(dem::non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(dem::non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        cohesion_(dem::non_negative(p, "cohesion_pa", where)),
        cohesion_std_(dem::non_negative_or(p, "cohesion_std_pa", 0.0, where)),
        tan_phi_(std::tan(dem::non_negative(p, "friction_angle_deg", where) * M_PI / 180.0)),
        joint_friction_(dem::non_negative(p, "joint_friction", where)),
        bonded_fraction_(dem::non_negative_or(p, "bonded_fraction", 1.0, where)) {
    if (bonded_fraction_ > 1) throw Error(where + ": \"bonded_fraction\" must lie in [0, 1]");
    if (dem::non_negative(p, "friction_angle_deg", where) >= 90)
      throw Error(where + ": \"friction_angle_deg\" must be below 90");
    const int radial = whole_number(p, "radial_elements", 1, kMaxRadial, where);
    const int circumferential = whole_number(p, "circumferential_elements", 3, kMaxCircumferential, where);
    if (radial * circumferential > kMaxElements)
      throw Error(where + ": \"radial_elements\" x \"circumferential_elements\" must be at most " +
                  std::to_string(kMaxElements) + " elements");
    elements_ = flat_joint::unit_disc_elements(radial, circumferential);
  }
  std::string name() const override { return "flat_joint"; }
  bool has_bonds() const override { return true; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"joint", "joint_kn_pa_m", "joint_ks_pa_m", "joint_radius_m", "joint_frame_x",
                          "joint_frame_y", "joint_frame_z", "joint_bending_1_rad", "joint_bending_2_rad",
                          "joint_twist_rad"})
      columns.emplace_back(c);
    for (std::size_t e = 1; e <= elements_.size(); ++e)
      for (const char* c : {"gap_m", "shear_force_1_n", "shear_force_2_n", "bonded", "tensile_strength_pa",
                            "cohesion_pa"})
        columns.push_back("element" + std::to_string(e) + "_" + c);
    return columns;
  }

  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const override {
    LinearBase::initialise(c, k, pair);
    c.column[kJoint][k] = 0.0;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, Rng& rng) const override {
    if (pair.wall) return false;
    c.column[kJoint][k] = 1.0;
    c.column[kJointRadius][k] = lambda_ * std::min(pair.radius_i, pair.radius_j);
    c.column[kJointKn][k] = joint_modulus_pa_ / (pair.radius_i + pair.radius_j);
    c.column[kJointKs][k] = c.column[kJointKn][k] / joint_kn_ks_;
    for (std::size_t column = kFrameX; column <= kTwist; ++column) c.column[column][k] = 0.0;
    for (std::size_t e = 0; e < elements_.size(); ++e) {
      c.column[column_of(e, kGap)][k] = 0.0;
      c.column[column_of(e, kShear1)][k] = c.column[column_of(e, kShear2)][k] = 0.0;
      c.column[column_of(e, kBondedElement)][k] = 1.0;
      c.column[column_of(e, kTensile)][k] = dem::draw_strength(sigma_c_, sigma_c_std_, rng);
      c.column[column_of(e, kCohesion)][k] = dem::draw_strength(cohesion_, cohesion_std_, rng);
    }
    // Slit elements (PFC3D's flat-jointed material installs a share unbonded),
    // drawn after the strengths so a joint's strengths do not depend on phi_B.
    bool any_bonded = true;
    if (bonded_fraction_ < 1) {
      any_bonded = false;
      for (std::size_t e = 0; e < elements_.size(); ++e) {
        const bool bonded = rng.uniform() < bonded_fraction_;
        c.column[column_of(e, kBondedElement)][k] = bonded ? 1.0 : 0.0;
        any_bonded = any_bonded || bonded;
      }
    }
    if (!any_bonded) {  // all slit: a contact like any other (its faces are not held)
      c.column[kJoint][k] = 0.0;
      return false;
    }
    c.flags[k] |= dem::kBonded;
    return true;
  }

  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    // A joint holds its pair until it has broken and parted (not only while bonded).
    for_held_pairs(
        c, s, out, step.dt_s, [&](std::size_t k) { return c.column[kJoint][k] != 0.0; },
        [&](std::size_t k, const PairContact& p) {
          joint(c, k, out, p, s.spin(static_cast<std::size_t>(c.j[k])) - s.spin(static_cast<std::size_t>(c.i[k])),
                step.dt_s);
        });
  }

  // An intact joint's springs are a parallel bond's of the same disc; the
  // linear contact's bound the step too (a broken joint's pairs take it).
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    LinearBase::stiffness(c, k, arm_m, translational_n_m, rotational_nm_rad);
    if (c.column[kJoint][k] == 0.0) return;
    const double r = c.column[kJointRadius][k], area = M_PI * r * r, inertia = 0.25 * area * r * r;
    const double normal = c.column[kJointKn][k] * area, shear = c.column[kJointKs][k] * area;
    translational_n_m = std::max({translational_n_m, normal, shear});
    rotational_nm_rad = std::max(rotational_nm_rad, shear * arm_m * arm_m +
                                                        std::max(c.column[kJointKn][k] * inertia,
                                                                 c.column[kJointKs][k] * 2 * inertia));
  }
  double stiffness_estimate(double radius_m) const override {
    const double r = lambda_ * radius_m;
    const double kn = joint_modulus_pa_ / (2.0 * radius_m) * M_PI * r * r;
    return std::max(LinearBase::stiffness_estimate(radius_m), kn * std::max(1.0, 1.0 / joint_kn_ks_));
  }

  double max_bond_utilisation(const ConstPairBlock& c, const Spheres&) const override {
    double most = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      if (!(c.flags[k] & dem::kBonded)) continue;
      const double r = c.column[kJointRadius][k];
      for (std::size_t e = 0; e < elements_.size(); ++e) {
        if (c.column[column_of(e, kBondedElement)][k] == 0.0) continue;
        const double area = elements_[e].area * r * r;
        const double sigma = c.column[kJointKn][k] * c.column[column_of(e, kGap)][k];
        const double tau = std::hypot(c.column[column_of(e, kShear1)][k], c.column[column_of(e, kShear2)][k]) / area;
        most = std::max({most, dem::utilisation(sigma, c.column[column_of(e, kTensile)][k]),
                         dem::utilisation(tau, c.column[column_of(e, kCohesion)][k] - sigma * tan_phi_)});
      }
    }
    return most;
  }

 private:
  // One joint's step. Forces and moments are summed in the joint's frame
  // (force on i; moments on i about the contact point) and turned to the
  // world's at the end.
  void joint(PairBlock& c, std::size_t k, const PairForces& out, const PairContact& p, Vec3 relative_spin,
             double dt_s) const {
    const Vec3 n = p.normal;
    Vec3 t1{c.column[kFrameX][k], c.column[kFrameY][k], c.column[kFrameZ][k]};
    if (t1.x == 0 && t1.y == 0 && t1.z == 0) {
      t1 = first_frame_vector(n);
    } else {
      t1 = turned_shear(t1, n, p.plane_spin_rad_s, dt_s);
      t1 = (1.0 / norm(t1)) * t1;
    }
    c.column[kFrameX][k] = t1.x, c.column[kFrameY][k] = t1.y, c.column[kFrameZ][k] = t1.z;
    const Vec3 t2 = cross(n, t1);
    const Vec3 v = p.relative_velocity_m_s;
    const double vn = dot(v, n), v1 = dot(v, t1), v2 = dot(v, t2);
    const double w1 = dot(relative_spin, t1), w2 = dot(relative_spin, t2), wn = dot(relative_spin, n);
    double& theta1 = c.column[kBend1][k];
    double& theta2 = c.column[kBend2][k];
    double& twist = c.column[kTwist][k];
    theta1 += w1 * dt_s, theta2 += w2 * dt_s, twist += wn * dt_s;

    const double r = c.column[kJointRadius][k], r2 = r * r, r4 = r2 * r2;
    const double kn = c.column[kJointKn][k], ks = c.column[kJointKs][k];
    double f1 = 0, f2 = 0, fn = 0, m1 = 0, m2 = 0, mn = 0;  // on i: force along t1, t2, n; moment
    bool any_bonded = false, pressed = false;
    dem::PairFlags flags = c.flags[k];
    for (std::size_t e = 0; e < elements_.size(); ++e) {
      const flat_joint::Element& shape = elements_[e];
      const double area = shape.area * r2, x1 = shape.x1 * r, x2 = shape.x2 * r;
      double& gap = c.column[column_of(e, kGap)][k];
      double& s1 = c.column[column_of(e, kShear1)][k];
      double& s2 = c.column[column_of(e, kShear2)][k];
      double& bonded = c.column[column_of(e, kBondedElement)][k];
      gap += (vn + w1 * x2 - w2 * x1) * dt_s;
      s1 += ks * area * (v1 - wn * x2) * dt_s;
      s2 += ks * area * (v2 + wn * x1) * dt_s;
      double normal = 0, b1 = 0, b2 = 0, twisting = 0;  // on i: normal force (tension > 0), own moments
      if (bonded != 0.0) {
        const double sigma = kn * gap;
        const double tau_c = c.column[column_of(e, kCohesion)][k] - sigma * tan_phi_;
        if (sigma > c.column[column_of(e, kTensile)][k]) {
          bonded = 0.0;
          flags = mark_break(flags, true);
        } else if (s1 * s1 + s2 * s2 > tau_c * area * tau_c * area || tau_c < 0) {
          bonded = 0.0;
          flags = mark_break(flags, false);
        } else {
          normal = kn * area * gap;
          section_bending(shape, kn * r4, theta1, theta2, b1, b2);
          twisting = ks * r4 * (shape.s11 + shape.s22) * twist;
          any_bonded = true;
          pressed = pressed || gap < 0;
        }
      }
      if (bonded == 0.0) {
        pressed_face(shape, r, kn, gap, theta1, theta2, normal, b1, b2);
        const double limit = -joint_friction_ * normal, size2 = s1 * s1 + s2 * s2;
        if (size2 > limit * limit) {
          const double scale = limit > 0 ? limit / std::sqrt(size2) : 0.0;
          s1 *= scale, s2 *= scale;
        }
        pressed = pressed || normal < 0;
      }
      f1 += s1, f2 += s2, fn += normal;
      // x_e x F_e with x_e = (x1, x2, 0) and F_e = (s1, s2, normal), plus the element's own moments.
      m1 += x2 * normal + b1, m2 += -x1 * normal + b2, mn += x1 * s2 - x2 * s1 + twisting;
    }
    if (!any_bonded) flags &= ~static_cast<dem::PairFlags>(dem::kBonded);
    flags &= ~static_cast<dem::PairFlags>(dem::kTouching);
    if (pressed) flags |= dem::kTouching;
    c.flags[k] = flags;
    const Vec3 force = f1 * t1 + f2 * t2 + fn * n;
    set_contact_force(out, k, p, force, force, m1 * t1 + m2 * t2 + mn * n);
    // A fully broken joint whose faces have parted is a linear contact from
    // now on, as a pair that meets later is: one law for a broken joint,
    // whether or not it then leaves the neighbour list.
    if (!any_bonded && !pressed) {
      c.column[kJoint][k] = 0.0;
      forget_shear(c, k);
    }
  }

  // The moment (on i, along t1 and t2) of an element's whole face bent by
  // theta about its centroid: k_n S_e theta with S_e its second moments,
  // `kn_r4` = k_n R_j^4 (S_e is per unit disc).
  static void section_bending(const flat_joint::Element& shape, double kn_r4, double theta1, double theta2,
                              double& b1, double& b2) {
    b1 = kn_r4 * (theta1 * shape.s22 - theta2 * shape.s12);
    b2 = kn_r4 * (theta2 * shape.s11 - theta1 * shape.s12);
  }

  // A broken element: compression only where its faces overlap, the gap
  // varying as gap + theta1 u2 - theta2 u1 across it (u from its centroid).
  // Sets its normal force (on i, < 0 pressed) and its own bending moment.
  static void pressed_face(const flat_joint::Element& shape, double r, double kn, double gap, double theta1,
                           double theta2, double& normal, double& b1, double& b2) {
    const double a1 = -theta2 * r, a2 = theta1 * r;  // the gap's slope over the unit element
    const auto [lo, hi] = shape.extent(a1, a2);
    normal = b1 = b2 = 0;
    if (gap + lo >= 0) return;  // open everywhere
    const double r2 = r * r, r3 = r2 * r, r4 = r2 * r2;
    if (gap + hi <= 0) {  // pressed everywhere: the bonded law in compression
      normal = kn * shape.area * r2 * gap;
      section_bending(shape, kn * r4, theta1, theta2, b1, b2);
      return;
    }
    // Over the sub-cells: a cell pressed all over adds its exact share (the
    // gap is linear); a cell the zero line crosses, its pressed part with the
    // gap taken as spread evenly between the cell's extremes (within 1.5e-3
    // of the disc's force and 6e-3 of its moment against the closed form; a
    // finer grid costs more than it gains: the sub-cells are the broken
    // joints' main cost).
    double sum = 0, sum_u1 = 0, sum_u2 = 0;  // of area x gap where pressed, and its moments about the centroid
    for (const flat_joint::SubCell& cell : shape.cells) {
      const double g = gap + a1 * cell.u1 + a2 * cell.u2;
      const double half_range = 0.5 * (std::abs(a1 * cell.radial1 + a2 * cell.radial2) * cell.depth +
                                        std::abs(a2 * cell.radial1 - a1 * cell.radial2) * cell.width);
      if (g - half_range >= 0) continue;
      if (g + half_range <= 0) {
        sum += cell.area * g;
        sum_u1 += cell.area * g * cell.u1 + cell.s11 * a1 + cell.s12 * a2;
        sum_u2 += cell.area * g * cell.u2 + cell.s12 * a1 + cell.s22 * a2;
        continue;
      }
      const double low = g - half_range, share = cell.area * low * low / (-4 * half_range);
      sum += share, sum_u1 += share * cell.u1, sum_u2 += share * cell.u2;
    }
    normal = kn * r2 * sum;
    b1 = kn * r3 * sum_u2;
    b2 = -kn * r3 * sum_u1;
  }

  double joint_modulus_pa_, joint_kn_ks_, lambda_;
  double sigma_c_, sigma_c_std_, cohesion_, cohesion_std_, tan_phi_, joint_friction_, bonded_fraction_;
  std::vector<flat_joint::Element> elements_;
};

}  // namespace

void register_flat_joint_model(ContactModelRegistry& registry) {
  registry.add("flat_joint", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction", "joint_modulus_pa",
                              "joint_kn_ks", "radius_multiplier", "radial_elements", "circumferential_elements",
                              "tensile_strength_pa", "tensile_strength_std_pa", "cohesion_pa", "cohesion_std_pa",
                              "friction_angle_deg", "joint_friction", "bonded_fraction"},
               [](const nlohmann::json& p, const std::string& where) {
                 return std::make_unique<FlatJointModel>(p, where);
               });
  // PFC3D's flatjoint (fj_nr x fj_na elements over the disc); the linear
  // part is what contacts formed later take.
  registry.set_peer_names("flat_joint", nlohmann::json::parse(R"({
    "pfc": {"model": "flatjoint",
      "keywords": [{"key": "joint_modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "joint_kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "tensile_strength_pa", "group": "property", "name": "fj_ten"},
                   {"key": "cohesion_pa", "group": "property", "name": "fj_coh"},
                   {"key": "friction_angle_deg", "group": "property", "name": "fj_fa"},
                   {"key": "joint_friction", "group": "property", "name": "fj_fric"},
                   {"key": "radial_elements", "group": "property", "name": "fj_nr", "as": "integer", "default": 1},
                   {"key": "circumferential_elements", "group": "property", "name": "fj_na", "as": "integer", "default": 3},
                   {"key": "radius_multiplier", "group": "property", "name": "fj_rmul", "default": 1},
                   {"key": "bonded_fraction", "group": "material", "name": "phi_B", "default": 1},
                   {"key": "modulus_pa", "group": "unjoined", "name": "emod"},
                   {"key": "kn_ks", "group": "unjoined", "name": "kratio"},
                   {"key": "kn_n_m", "group": "unjoined", "name": "kn"},
                   {"key": "ks_n_m", "group": "unjoined", "name": "ks"},
                   {"key": "friction", "group": "unjoined", "name": "fric"}],
      "later": {"unjoined": {"text": "contacts that form later (unjoined) take the linear part"},
                "material": {"text": "the share of elements installed bonded, the flat-jointed material's phi_B: set each element's state at installation"}}},
    "yade": {"model": "CohFrictMat", "notes": ["no flat joint in YADE: its elements, partial damage and friction angle do not carry over; a cohesive-frictional bond is the nearest"],
      "keywords": [{"key": "joint_modulus_pa", "name": "young"}, {"key": "joint_kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "joint_friction", "name": "frictionAngle", "as": "atan"},
                   {"key": "tensile_strength_pa", "name": "normalCohesion"},
                   {"key": "cohesion_pa", "name": "shearCohesion"}, {"name": "isCohesive", "value": true}]}})"));
}

}  // namespace demcal::dem3d
