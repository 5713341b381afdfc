// The linear contact model in 3D (PFC3D's linear model by the deformability
// method): kn = A E* / L with A = pi r^2, r = min(R_i, R_j), L = R_i + R_j
// (a sphere on a wall: r = L = R), ks = kn / (kn/ks), or the springs given
// directly; Coulomb friction; no dashpots.
//   parameters: {"modulus_pa": E*, "kn_ks": kn/ks, "friction": mu} or
//               {"kn_n_m", "ks_n_m", "friction"}
//   state: kn_n_m, ks_n_m, friction, reference_overlap_m, the shear force vector.
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem3d/contact_model.hpp"
#include "demcal/dem3d/linear_contact.hpp"
#include "demcal/dem3d/pair_contact.hpp"

namespace demcal::dem3d {
namespace {

enum Column : std::size_t { kKn, kKs, kFriction, kReferenceOverlap, kShearX, kShearY, kShearZ, kColumns };

double number(const nlohmann::json& p, const char* key, const std::string& where) {
  if (!p.contains(key)) throw Error(where + ": missing parameter \"" + key + "\"");
  if (!p.at(key).is_number() || !std::isfinite(p.at(key).get<double>()))
    throw Error(where + ": parameter \"" + key + "\" must be a finite number");
  return p.at(key).get<double>();
}

class LinearModel : public ContactModel {
 public:
  LinearModel(const nlohmann::json& p, const std::string& where) {
    friction_ = number(p, "friction", where);
    if (friction_ < 0) throw Error(where + ": friction must be >= 0");
    const bool springs = p.contains("kn_n_m") || p.contains("ks_n_m");
    if (springs == (p.contains("modulus_pa") || p.contains("kn_ks")))
      throw Error(where + ": give either modulus_pa and kn_ks (the deformability method) or kn_n_m and ks_n_m");
    if (springs) {
      kn_ = number(p, "kn_n_m", where), ks_ = number(p, "ks_n_m", where);
      if (!(kn_ > 0) || !(ks_ >= 0)) throw Error(where + ": kn_n_m must be > 0 and ks_n_m >= 0");
    } else {
      modulus_ = number(p, "modulus_pa", where), kn_ks_ = number(p, "kn_ks", where);
      if (!(modulus_ > 0) || !(kn_ks_ > 0)) throw Error(where + ": modulus_pa and kn_ks must be > 0");
    }
  }
  std::string name() const override { return "linear"; }
  std::vector<std::string> state_columns() const override {
    return {"kn_n_m", "ks_n_m", "friction", "reference_overlap_m", "shear_force_x_n", "shear_force_y_n",
            "shear_force_z_n"};
  }
  void initialise(PairBlock& c, std::size_t k, const PairInfo& pair) const override {
    double kn = kn_, ks = ks_;
    if (modulus_ > 0) {
      const double r = pair.wall ? pair.radius_i : std::min(pair.radius_i, pair.radius_j);
      const double length = pair.radius_i + pair.radius_j;  // radius_j = 0 for a wall
      kn = M_PI * r * r * modulus_ / length;
      ks = kn / kn_ks_;
    }
    c.column[kKn][k] = kn;
    c.column[kKs][k] = ks;
    c.column[kFriction][k] = friction_;
  }
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    for_sphere_pairs(
        c, s, [&](std::size_t k, const PairContact& p) { touch(c, k, out, p, step.dt_s); },
        [&](std::size_t k) { leave(c, k, out); });
  }
  void wall_forces(PairBlock& c, const Spheres& s, const WallGeometry& g, const PairForces& out,
                   const StepContext& step) const override {
    for_wall_pairs(
        c, s, g, [&](std::size_t k, const PairContact& p) { touch(c, k, out, p, step.dt_s); },
        [&](std::size_t k) { leave(c, k, out); });
  }
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    // The stiffer spring bounds translation (kn/ks may be below 1); the shear
    // spring acts at the contact point, `arm_m` from the centre.
    translational_n_m = std::max(c.column[kKn][k], c.column[kKs][k]);
    rotational_nm_rad = c.column[kKs][k] * arm_m * arm_m;
  }
  double stiffness_estimate(double radius_m) const override {
    if (modulus_ <= 0) return std::max(kn_, ks_);
    const double kn = M_PI * radius_m * radius_m * modulus_ / (2 * radius_m);
    return std::max(kn, kn / kn_ks_);
  }

 private:
  // A pair out of contact: no force, and its shear force forgotten.
  static void leave(PairBlock& c, std::size_t k, const PairForces& out) {
    c.column[kShearX][k] = c.column[kShearY][k] = c.column[kShearZ][k] = 0;
    c.flags[k] &= ~static_cast<dem::PairFlags>(dem::kTouching);
    out.set(k, {}, {}, {});
  }
  [[gnu::always_inline]] static inline void touch(PairBlock& c, std::size_t k, const PairForces& out,
                                                  const PairContact& p, double dt_s) {
    LinearContactInput in{p.normal, p.overlap_m, p.arm_i_m, p.relative_velocity_m_s, p.mean_spin_rad_s, 0, 0, 0, 0, dt_s};
    const double arm_j = p.arm_j_m;
    in.kn_n_m = c.column[kKn][k];
    in.ks_n_m = c.column[kKs][k];
    in.friction = c.column[kFriction][k];
    in.reference_overlap_m = c.column[kReferenceOverlap][k];
    double fn = 0;
    const Vec3 fs = linear_shear_force(in, {c.column[kShearX][k], c.column[kShearY][k], c.column[kShearZ][k]}, fn);
    c.column[kShearX][k] = fs.x, c.column[kShearY][k] = fs.y, c.column[kShearZ][k] = fs.z;
    c.flags[k] |= dem::kTouching;
    // On i: the normal force pushes it away from j; the shear force acts at the
    // contact point, in_arm_i along the normal (j's moment: arm_j, opposite side, opposite force).
    const Vec3 force = fs - fn * in.normal;
    const Vec3 n_cross_fs = cross(in.normal, fs);
    out.set(k, force, in.arm_i_m * n_cross_fs, arm_j * n_cross_fs);
  }

  double modulus_ = 0, kn_ks_ = 0, kn_ = 0, ks_ = 0, friction_ = 0;
};

}  // namespace

void register_linear_model(ContactModelRegistry& registry) {
  registry.add("linear", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction"},
               [](const nlohmann::json& p, const std::string& where) { return std::make_unique<LinearModel>(p, where); });
  // PFC3D's linear model by the deformability method (or its kn and ks).
  registry.set_peer_names("linear", nlohmann::json::parse(R"({
    "pfc": {"model": "linear",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "kn_n_m", "group": "property", "name": "kn"},
                   {"key": "ks_n_m", "group": "property", "name": "ks"},
                   {"key": "friction", "group": "property", "name": "fric"}]}})"));
}

}  // namespace demcal::dem3d
