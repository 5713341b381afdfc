#pragma once
// The linear contact as the 3D models built on it share it (linear, contact
// bond, parallel bond): its parameters (PFC3D's deformability method kn =
// pi r^2 E* / (R_i + R_j), r = min(R), ks = kn / (kn/ks); or kn and ks given),
// its state columns, which come first in each such model's state, and its law
// on a touching pair.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/linear_contact.hpp"
#include "demcal/dem3d/pair_contact.hpp"

namespace demcal::dem3d {

enum LinearColumn : std::size_t {
  kKn,                // N/m
  kKs,                // N/m
  kFriction,          //
  kReferenceOverlap,  // m: the overlap at which the normal spring is slack
  kShearX,            // shear force on i, N
  kShearY,
  kShearZ,
  kLinearColumns
};

class LinearBase : public ContactModel {
 public:
  LinearBase(const nlohmann::json& p, const std::string& where);
  std::vector<std::string> state_columns() const override;
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const override;
  void make_force_free(PairBlock& c, std::size_t k, double overlap_m) const override;
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override;
  double stiffness_estimate(double radius_m) const override;
  // Walls carry no bonds: every such model's wall pairs follow the linear law.
  void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                   const StepContext& step) const override {
    for_wall_pairs(
        c, s, g, [&](std::size_t k, const PairContact& p) { linear_touch(c, k, out, p, step.dt_s); },
        [&](std::size_t k) { linear_leave(c, k, out); });
  }

 protected:
  // A pair out of contact: no force, and its shear force forgotten.
  static void linear_leave(PairBlock& c, std::size_t k, const PairForces& out) {
    forget_shear(c, k);
    c.flags[k] &= ~static_cast<dem::PairFlags>(dem::kTouching);
    out.set(k, {}, {}, {});
  }
  // A touching pair under the linear law alone.
  [[gnu::always_inline]] static inline void linear_touch(PairBlock& c, std::size_t k, const PairForces& out,
                                                         const PairContact& p, double dt_s) {
    double fn = 0;
    const Vec3 fs = linear_forces(c, k, p, dt_s, fn);
    c.flags[k] |= dem::kTouching;
    // On i: the normal force pushes it away from j; the shear force acts at the
    // contact point, arm_i along the normal (j's moment: arm_j, opposite side, opposite force).
    const Vec3 force = fs - fn * p.normal;
    const Vec3 n_cross_fs = cross(p.normal, fs);
    out.set(k, force, p.arm_i_m * n_cross_fs, p.arm_j_m * n_cross_fs);
  }
  // The linear law of the touching pair k: its shear force updated in its
  // state and returned (force on i), `normal_force_n` its normal force.
  [[gnu::always_inline]] static inline Vec3 linear_forces(PairBlock& c, std::size_t k, const PairContact& p,
                                                          double dt_s, double& normal_force_n) {
    LinearContactInput in{p.normal, p.overlap_m, p.arm_i_m, p.relative_velocity_m_s, p.plane_spin_rad_s, 0, 0, 0, 0, dt_s};
    in.kn_n_m = c.column[kKn][k];
    in.ks_n_m = c.column[kKs][k];
    in.friction = c.column[kFriction][k];
    in.reference_overlap_m = c.column[kReferenceOverlap][k];
    const Vec3 fs = linear_shear_force(in, {c.column[kShearX][k], c.column[kShearY][k], c.column[kShearZ][k]},
                                       normal_force_n);
    c.column[kShearX][k] = fs.x, c.column[kShearY][k] = fs.y, c.column[kShearZ][k] = fs.z;
    return fs;
  }
  // A block whose pairs are held (`is_held(k)`: bonded, joined) or not: a
  // pair not held follows the linear law, a held one `held(k, geometry)`
  // whether its spheres touch or not (a bond holds them across a gap).
  template <class IsHeld, class Held>
  static void for_held_pairs(PairBlock& c, const Spheres& s, const PairForces& out, double dt_s, IsHeld is_held,
                             Held held) {
    PairContact p;
    for (std::size_t k = 0; k < c.size; ++k) {
      const auto i = static_cast<std::size_t>(c.i[k]), j = static_cast<std::size_t>(c.j[k]);
      if (!is_held(k)) {
        if (sphere_pair_contact(s, i, j, p))
          linear_touch(c, k, out, p, dt_s);
        else
          linear_leave(c, k, out);
        continue;
      }
      sphere_pair_geometry(s, i, j, p);
      held(k, p);
    }
  }
  // A bonded model's block: the pairs with an intact bond are held.
  template <class Bonded>
  static void for_bondable_pairs(PairBlock& c, const Spheres& s, const PairForces& out, double dt_s, Bonded bonded) {
    for_held_pairs(
        c, s, out, dt_s, [&](std::size_t k) { return (c.flags[k] & dem::kBonded) != 0; }, bonded);
  }
  static void forget_shear(PairBlock& c, std::size_t k) {
    c.column[kShearX][k] = c.column[kShearY][k] = c.column[kShearZ][k] = 0;
  }
  double linear_kn(const PairInfo& pair) const;
  double linear_ks(double kn) const { return modulus_ > 0 ? kn / kn_ks_ : ks_; }

  double modulus_ = 0, kn_ks_ = 0, kn_ = 0, ks_ = 0, friction_ = 0;
};

// The force on i and the moments about both centres of a force `force` (on
// i) whose shear part `fs` acts at the contact point.
inline void set_contact_force(const PairForces& out, std::size_t k, const PairContact& p, Vec3 force, Vec3 fs,
                              Vec3 extra_moment_i = {}) {
  const Vec3 n_cross_fs = cross(p.normal, fs);
  out.set(k, force, p.arm_i_m * n_cross_fs + extra_moment_i, p.arm_j_m * n_cross_fs - extra_moment_i);
}

}  // namespace demcal::dem3d
