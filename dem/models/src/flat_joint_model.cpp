// Flat joint (Potyondy 2012), 2D: a bonded pair is joined across a flat
// interface of length 2 R_j (R_j = lambda min(R_i, R_j)) split into N equal
// elements. Each element is bonded (tensile strength, Mohr-Coulomb shear
// strength c - sigma tan(phi_b)) or, once broken, frictional (no tension,
// |F_s| <= mu F_n); a bond breaks element by element (partial damage), and a
// broken interface stays flat, so it still resists rotation where it is
// pressed together. That is what lets it reach the high UCS / tensile
// strength ratios of rock, where a parallel bond gives about 4.
//   parameters: {"modulus_pa", "kn_ks", "friction"   (the linear contact of pairs that meet during the test),
//                "joint_modulus_pa", "joint_kn_ks",   (kn = E_j / (R_i + R_j) and ks = kn / (kn/ks)_j per area)
//                "radius_multiplier" (lambda, default 1), "elements" (N, 1-6, default 2),
//                "tensile_strength_pa", "tensile_strength_std_pa" (default 0),
//                "cohesion_pa", "cohesion_std_pa" (default 0), "friction_angle_deg" (phi_b of bonded elements),
//                "joint_friction" (mu of broken elements)}
// Kinematics, incremental from installation (where the interface is
// force-free): with theta the rotation of j relative to i and x_e the
// centre of element e along t, its opening grows by (v_n - w_rel x_e) dt and
// its shear force by -k_s A_e v_s dt. A bonded element carries F_n = -k_n A_e
// gap and, for the rotation inside it, a moment -k_n I_e theta (I_e =
// w_e^3 t / 12), so an intact joint bends like a parallel bond (sum of A_e
// x_e^2 + I_e = 2/3 R_j^3 t). Its average stress sigma = k_n gap (tension
// positive) is checked against its strengths (broken strictly beyond them, so
// a zero strength breaks an element at its first tension or shear, never at
// rest); a broken element carries compression only, where its faces overlap:
// the gap varies as gap - theta u across it, so a pressed broken element
// still resists rotation (one element fully broken included). Every element
// break is logged as a crack; the pair stays a joint (held in the neighbour
// list) while an element is bonded. A fully broken joint whose faces have
// parted everywhere becomes a linear contact at once, as a pair that meets
// during the test is: its law never depends on the neighbour list.
#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/bond_law.hpp"
#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/linear_base.hpp"
#include "demcal/dem/model_parameters.hpp"

namespace demcal::dem {
namespace {

constexpr int kMaxElements = 6;

enum JointColumn : std::size_t {
  kJoint = kLinearColumns,  // 1 for an installed joint, 0 for a linear contact
  kJointKn,                 // normal stiffness per area, Pa/m
  kJointKs,                 // shear stiffness per area, Pa/m
  kJointRadius,             // R_j, m
  kJointArea,               // 2 R_j t, m^2
  kJointRotation,           // theta since installation, rad
  kElementColumns           // then per element: gap, shear force, bonded, tensile strength, cohesion
};
enum ElementColumn : std::size_t { kGap = 0, kShear, kBondedElement, kTensile, kCohesion, kPerElement };

class FlatJointModel : public LinearBase {
 public:
  FlatJointModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        joint_modulus_pa_(positive(p, "joint_modulus_pa", where)),
        joint_kn_ks_(positive(p, "joint_kn_ks", where)),
        lambda_(p.contains("radius_multiplier") ? positive(p, "radius_multiplier", where) : 1.0),
        sigma_c_(non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        cohesion_(non_negative(p, "cohesion_pa", where)),
        cohesion_std_(non_negative_or(p, "cohesion_std_pa", 0.0, where)),
        tan_phi_(std::tan(non_negative(p, "friction_angle_deg", where) * M_PI / 180.0)),
        joint_friction_(non_negative(p, "joint_friction", where)) {
    const double n = p.contains("elements") ? positive(p, "elements", where) : 2.0;
    if (n != std::floor(n) || n > kMaxElements)
      throw Error(where + ": \"elements\" must be a whole number from 1 to " + std::to_string(kMaxElements));
    elements_ = static_cast<int>(n);
    if (non_negative(p, "friction_angle_deg", where) >= 90)
      throw Error(where + ": \"friction_angle_deg\" must be below 90");
  }
  std::string name() const override { return "flat_joint"; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"joint", "joint_kn_pa_m", "joint_ks_pa_m", "joint_radius_m", "joint_area_m2", "joint_rotation_rad"})
      columns.emplace_back(c);
    for (int e = 1; e <= elements_; ++e)
      for (const char* c : {"gap_m", "shear_force_n", "bonded", "tensile_strength_pa", "cohesion_pa"})
        columns.push_back("element" + std::to_string(e) + "_" + c);
    return columns;
  }

  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m) const override {
    LinearBase::initialise(c, k, pair, thickness_m);
    c.column[kJoint][k] = 0.0;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, double thickness_m, Rng& rng) const override {
    if (pair.wall) return false;
    c.column[kJoint][k] = 1.0;
    c.column[kJointRadius][k] = lambda_ * std::min(pair.radius_i, pair.radius_j);
    c.column[kJointArea][k] = 2.0 * c.column[kJointRadius][k] * thickness_m;
    c.column[kJointKn][k] = joint_modulus_pa_ / (pair.radius_i + pair.radius_j);
    c.column[kJointKs][k] = c.column[kJointKn][k] / joint_kn_ks_;
    c.column[kJointRotation][k] = 0.0;
    for (int e = 0; e < elements_; ++e) {
      c.column[element(e, kGap)][k] = 0.0;
      c.column[element(e, kShear)][k] = 0.0;
      c.column[element(e, kBondedElement)][k] = 1.0;
      c.column[element(e, kTensile)][k] = draw_strength(sigma_c_, sigma_c_std_, rng);
      c.column[element(e, kCohesion)][k] = draw_strength(cohesion_, cohesion_std_, rng);
    }
    c.flags[k] |= kBonded;
    return true;
  }

  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    const double dt = step.dt_s;
    for_disk_pairs(
        c, b, step,
        [&](std::size_t k, const Geometry& g) {
          if (c.column[kJoint][k] == 0.0) return linear_force(c, k, g, dt);
          return joint_force(c, k, g, b, step);
        },
        [&](std::size_t k, double gap) { return c.column[kJoint][k] == 0.0 && skip_apart(c, k, gap); });
  }

  // An intact joint adds its springs like a parallel bond of the same
  // geometry (exact bending: the sum of A_e x_e^2 + I_e is 2/3 R_j^3 t).
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    LinearBase::stiffness(c, k, arm_m, translational_n_m, rotational_nm_rad);
    if (c.column[kJoint][k] == 0.0) return;
    const double rj = c.column[kJointRadius][k], area = c.column[kJointArea][k];
    const double normal = c.column[kJointKn][k] * area, shear = c.column[kJointKs][k] * area;
    translational_n_m = std::max({translational_n_m, normal, shear});
    rotational_nm_rad = std::max(rotational_nm_rad, shear * arm_m * arm_m + c.column[kJointKn][k] * area * rj * rj / 3.0);
  }

  double normal_force_n(const ConstPairBlock& c, std::size_t k, double overlap_m) const override {
    if (c.column[kJoint][k] == 0.0) return LinearBase::normal_force_n(c, k, overlap_m);
    const double area_e = c.column[kJointArea][k] / elements_;
    double sum = 0;
    for (int e = 0; e < elements_; ++e) sum += std::max(0.0, -c.column[kJointKn][k] * area_e * c.column[element(e, kGap)][k]);
    return sum;
  }

  double stiffness_estimate(double radius_m, double thickness_m) const override {
    const double kn = joint_modulus_pa_ / (2.0 * radius_m) * 2.0 * lambda_ * radius_m * thickness_m;
    return LinearBase::stiffness_estimate(radius_m, thickness_m) + kn * std::max(1.0, 1.0 / joint_kn_ks_);
  }

 private:
  static std::size_t element(int e, ElementColumn column) {
    return kElementColumns + static_cast<std::size_t>(e) * kPerElement + column;
  }

  PairForce joint_force(PairBlock& c, std::size_t k, const Geometry& g, const Bodies& b, const StepContext& step) const {
    const double kn = c.column[kJointKn][k], ks = c.column[kJointKs][k], rj = c.column[kJointRadius][k];
    const double width = 2.0 * rj / elements_, area = c.column[kJointArea][k] / elements_;
    const double inertia = area * width * width / 12.0;
    double& theta = c.column[kJointRotation][k];
    theta += g.relative_w * step.dt_s;
    PairForce f;
    bool any_bonded = false, open = true;
    for (int e = 0; e < elements_; ++e) {
      const double x = -rj + (e + 0.5) * width;  // the element's centre along t
      double& gap = c.column[element(e, kGap)][k];
      double& shear = c.column[element(e, kShear)][k];
      double& bonded = c.column[element(e, kBondedElement)][k];
      gap += (g.vn - g.relative_w * x) * step.dt_s;
      shear -= ks * area * g.vs * step.dt_s;
      double normal = 0, moment = 0;  // compression > 0; couple on j
      if (bonded != 0.0) {
        const double sigma = kn * gap;  // average normal stress, tension > 0
        const double tau_c = c.column[element(e, kCohesion)][k] - sigma * tan_phi_;
        // Strictly beyond a strength: a zero strength is none (the first tension or shear breaks the element),
        // not a break of an unloaded element.
        if (sigma > c.column[element(e, kTensile)][k]) {
          bonded = 0.0;
          log_break(c, k, g, b, step, BreakMode::Tension);
        } else if (std::abs(shear) > tau_c * area) {
          bonded = 0.0;
          log_break(c, k, g, b, step, BreakMode::Shear);
        } else {
          normal = -kn * area * gap;
          moment = -kn * inertia * theta;
          any_bonded = true;
        }
      }
      if (bonded == 0.0) {
        // Broken: the faces push where they overlap (the gap varies as gap - theta u across the element, so a
        // pressed broken element resists rotation too) and slide on Coulomb friction.
        const Pressed pressed = pressed_part(gap, theta, width);
        normal = kn * step.thickness_m * pressed.force_per_kn;
        moment = -kn * step.thickness_m * pressed.moment_per_kn;
        const double limit = joint_friction_ * normal;
        if (std::abs(shear) > limit) shear = std::copysign(limit, shear);
        open = open && pressed.force_per_kn == 0.0;
      } else {
        open = false;
      }
      f.fn += normal;
      f.fs += shear;
      f.moment += moment - x * normal;
    }
    if (!any_bonded) c.flags[k] &= ~static_cast<PairFlags>(kBonded);
    // A fully broken joint whose faces have parted is a linear contact from
    // now on, as a pair that meets later is: one law for a broken joint,
    // whether or not it then leaves the neighbour list (and so whatever the skin).
    if (open) {
      c.column[kJoint][k] = 0.0;
      c.column[kShearForce][k] = 0.0;
    }
    return f;
  }

  // The compressed part of an element of width w whose faces stand apart by
  // gap - theta u at u in [-w/2, w/2] from its centre: the integrals of the
  // overlap (theta u - gap, where positive) and of the overlap times u, m^2
  // and m^3 per unit thickness (times k_n t: the force and the moment about
  // the element's centre).
  struct Pressed {
    double force_per_kn = 0, moment_per_kn = 0;
  };
  static Pressed pressed_part(double gap, double theta, double width) {
    double lo = -0.5 * width, hi = 0.5 * width;
    if (theta == 0.0) {
      if (gap >= 0) return {};
      return {-gap * width, 0.0};
    }
    const double zero = gap / theta;  // where the overlap changes sign
    if (theta > 0)
      lo = std::max(lo, zero);
    else
      hi = std::min(hi, zero);
    if (!(hi > lo)) return {};
    const double d1 = hi - lo, d2 = hi * hi - lo * lo, d3 = hi * hi * hi - lo * lo * lo;
    return {theta * d2 / 2.0 - gap * d1, theta * d3 / 3.0 - gap * d2 / 2.0};
  }

  // A broken element is a crack: logged like a bond break, the pair's flag
  // kept while other elements hold.
  static void log_break(const PairBlock& c, std::size_t k, const Geometry& g, const Bodies& b, const StepContext& step,
                        BreakMode mode) {
    if (step.breaks)
      step.breaks->push_back({step.time_s, g.cx, g.cy, mode, b.group[static_cast<std::size_t>(c.i[k])],
                              b.group[static_cast<std::size_t>(c.j[k])]});
  }

  double joint_modulus_pa_, joint_kn_ks_, lambda_;
  double sigma_c_, sigma_c_std_, cohesion_, cohesion_std_, tan_phi_, joint_friction_;
  int elements_ = 2;
};

}  // namespace

void register_flat_joint_model(ContactModelRegistry& registry) {
  registry.add("flat_joint", {"modulus_pa", "kn_ks", "friction", "joint_modulus_pa", "joint_kn_ks",
                               "radius_multiplier", "elements", "tensile_strength_pa", "tensile_strength_std_pa",
                               "cohesion_pa", "cohesion_std_pa", "friction_angle_deg", "joint_friction"}, [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<FlatJointModel>(p, where);
  });
  // PFC's flatjoint (fj_nr elements across the joint); the linear part is
  // what contacts formed later take. YADE has no flat joint.
  registry.set_peer_names("flat_joint", nlohmann::json::parse(R"({
    "pfc": {"model": "flatjoint",
      "keywords": [{"key": "joint_modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "joint_kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "tensile_strength_pa", "group": "property", "name": "fj_ten"},
                   {"key": "cohesion_pa", "group": "property", "name": "fj_coh"},
                   {"key": "friction_angle_deg", "group": "property", "name": "fj_fa"},
                   {"key": "joint_friction", "group": "property", "name": "fj_fric"},
                   {"key": "elements", "group": "property", "name": "fj_nr", "as": "integer", "default": 2},
                   {"key": "radius_multiplier", "group": "property", "name": "fj_rmul", "default": 1},
                   {"key": "modulus_pa", "group": "unjoined", "name": "emod"},
                   {"key": "kn_ks", "group": "unjoined", "name": "kratio"},
                   {"key": "friction", "group": "unjoined", "name": "fric"}],
      "later": {"unjoined": {"text": "contacts that form later (unjoined) take the linear part"}}},
    "yade": {"model": "CohFrictMat", "notes": ["no flat joint in YADE: its elements, partial damage and friction angle do not carry over; a cohesive-frictional bond is the nearest"],
      "keywords": [{"key": "joint_modulus_pa", "name": "young"}, {"key": "joint_kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "joint_friction", "name": "frictionAngle", "as": "atan"},
                   {"key": "tensile_strength_pa", "name": "normalCohesion"},
                   {"key": "cohesion_pa", "name": "shearCohesion"}, {"name": "isCohesive", "value": true}]},
    "liggghts": {"model": "hertz", "notes": ["LIGGGHTS-PUBLIC has no bonds: only the contact's stiffness and friction carry over"],
      "keywords": [{"key": "modulus_pa", "name": "youngsModulus"},
                   {"key": "kn_ks", "name": "poissonsRatio", "as": "hertz_mindlin_poisson"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem
