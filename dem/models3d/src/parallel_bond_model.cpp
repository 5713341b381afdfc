// Linear parallel bond in 3D (Potyondy & Cundall 2004; PFC3D's linearpbond)
// in parallel with a linear contact.
//   parameters: the linear model's, and "bond_modulus_pa", "bond_kn_ks",
//               "radius_multiplier" (lambda, default 1), "tensile_strength_pa",
//               "tensile_strength_std_pa" (default 0), "shear_strength_pa",
//               "shear_strength_std_pa" (default 0), "moment_contribution"
//               (beta, default 1)
// Bond: a cement disc of radius R_b = lambda min(R_i, R_j), A = pi R_b^2,
// I = pi R_b^4 / 4, J = pi R_b^4 / 2; kn_b = E_b / (R_i + R_j) and
// ks_b = kn_b / (kn/ks)_b per area. Its normal force, shear force vector,
// twisting moment and bending moment vector grow incrementally from zero at
// installation (the shear force and the bending moment turn with the contact
// plane, as the linear contact's shear force). It breaks in tension when
// sigma = -F_n / A + beta |M_b| R_b / I >= sigma_c, else in shear when
// tau = |F_s| / A + beta |M_t| R_b / J >= tau_c (PFC's pb_fa 0: no friction
// angle), and is gone: the linear contact alone remains.
//   state: the linear columns, then the bond's stiffnesses per area, radius,
//   forces and moments (on i) and the strengths drawn for it.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/bond_strength.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem3d/builtin_models.hpp"
#include "demcal/dem/select.hpp"
#include "demcal/dem3d/linear_base.hpp"
#include "demcal/dem3d/linear_batch.hpp"
#include "demcal/dem3d/sphere_records.hpp"

namespace demcal::dem3d {
namespace {

enum BondColumn : std::size_t {
  kBondKn = kLinearColumns,  // normal stiffness per area, Pa/m
  kBondKs,                   // shear stiffness per area, Pa/m
  kBondRadius,               // m
  kBondFn,                   // normal force, compression > 0, N
  kBondFsX,                  // shear force on i, N
  kBondFsY,
  kBondFsZ,
  kBondMt,                   // twisting moment on i about the normal, N m
  kBondMbX,                  // bending moment on i, N m
  kBondMbY,
  kBondMbZ,
  kTensileStrength,          // Pa
  kShearStrength,            // Pa
};

struct Section {
  double area, inertia, polar;  // A, I, J
};
inline Section section_of(double rb) {
  const double rb2 = rb * rb;
  return {M_PI * rb2, 0.25 * M_PI * rb2 * rb2, 0.5 * M_PI * rb2 * rb2};
}

class ParallelBondModel : public LinearBase {
 public:
  ParallelBondModel(const nlohmann::json& p, const std::string& where)
      : LinearBase(p, where),
        bond_modulus_pa_(dem::positive(p, "bond_modulus_pa", where)),
        bond_kn_ks_(dem::positive(p, "bond_kn_ks", where)),
        lambda_(p.contains("radius_multiplier") ? dem::positive(p, "radius_multiplier", where) : 1.0),
        sigma_c_(dem::non_negative(p, "tensile_strength_pa", where)),
        sigma_c_std_(dem::non_negative_or(p, "tensile_strength_std_pa", 0.0, where)),
        tau_c_(dem::non_negative(p, "shear_strength_pa", where)),
        tau_c_std_(dem::non_negative_or(p, "shear_strength_std_pa", 0.0, where)),
        beta_(dem::non_negative_or(p, "moment_contribution", 1.0, where)) {
    if (beta_ > 1) throw Error(where + ": moment_contribution must lie in [0, 1]");
  }
  std::string name() const override { return "parallel_bond"; }
  bool has_bonds() const override { return true; }

  std::vector<std::string> state_columns() const override {
    std::vector<std::string> columns = LinearBase::state_columns();
    for (const char* c : {"bond_kn_pa_m", "bond_ks_pa_m", "bond_radius_m", "bond_normal_force_n",
                          "bond_shear_force_x_n", "bond_shear_force_y_n", "bond_shear_force_z_n",
                          "bond_twisting_moment_nm", "bond_bending_moment_x_nm", "bond_bending_moment_y_nm",
                          "bond_bending_moment_z_nm", "bond_tensile_strength_pa", "bond_shear_strength_pa"})
      columns.emplace_back(c);
    return columns;
  }

  bool install_bond(PairBlock& c, std::size_t k, const PairInfo& pair, Rng& rng) const override {
    if (pair.wall) return false;
    c.column[kBondRadius][k] = lambda_ * std::min(pair.radius_i, pair.radius_j);
    c.column[kBondKn][k] = bond_modulus_pa_ / (pair.radius_i + pair.radius_j);
    c.column[kBondKs][k] = c.column[kBondKn][k] / bond_kn_ks_;
    for (std::size_t column = kBondFn; column <= kBondMbZ; ++column) c.column[column][k] = 0.0;
    c.column[kTensileStrength][k] = dem::draw_strength(sigma_c_, sigma_c_std_, rng);
    c.column[kShearStrength][k] = dem::draw_strength(tau_c_, tau_c_std_, rng);
    c.flags[k] |= dem::kBonded;
    return true;
  }

  // In batches (parallel_bond_batch below): the arithmetic of the scalar
  // law, pair by pair (for_bondable_pairs with linear_touch for a pair
  // without a bond, the bond law for one with it), vectorised.
  void sphere_forces(PairBlock& c, const Spheres& s, const PairForces& out, const StepContext& step) const override {
    std::vector<double> own;
    const double* records = step.records;
    if (!records) own = sphere_records(s), records = own.data();
    linear_batch::Batch b;
    alignas(64) std::int32_t broke[linear_batch::kBatch], tension[linear_batch::kBatch];
    for (std::size_t from = 0; from < c.size; from += linear_batch::kBatch) {
      const std::size_t n = std::min(linear_batch::kBatch, c.size - from);
      const bool any_broke = batch(c, records, from, n, step.dt_s, b, broke, tension);
      if (any_broke)
        for (std::size_t p = 0; p < n; ++p)
          if (broke[p]) c.flags[from + p] = mark_break(c.flags[from + p], tension[p] != 0);
      linear_batch::put_batch(out, from, n, b, nullptr);
    }
  }

  // The bond's springs in parallel with the contact's (kept after a break,
  // as a bound on the step): translation by the stiffer of the normal and
  // shear sums; rotation by the shear sum at the contact point plus the
  // stiffer of the bond's bending and twisting springs.
  void stiffness(const ConstPairBlock& c, std::size_t k, double arm_m, double& translational_n_m,
                 double& rotational_nm_rad) const override {
    const Section b = section_of(c.column[kBondRadius][k]);
    const double normal = c.column[kKn][k] + c.column[kBondKn][k] * b.area;
    const double shear = c.column[kKs][k] + c.column[kBondKs][k] * b.area;
    translational_n_m = std::max(normal, shear);
    rotational_nm_rad =
        shear * arm_m * arm_m + std::max(c.column[kBondKn][k] * b.inertia, c.column[kBondKs][k] * b.polar);
  }
  double stiffness_estimate(double radius_m) const override {
    const double bond_kn = bond_modulus_pa_ / (2.0 * radius_m) * section_of(lambda_ * radius_m).area;
    return LinearBase::stiffness_estimate(radius_m) + bond_kn * std::max(1.0, 1.0 / bond_kn_ks_);
  }

  double max_bond_utilisation(const ConstPairBlock& c, const Spheres&) const override {
    double most = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      if (!(c.flags[k] & dem::kBonded)) continue;
      double sigma = 0, tau = 0;
      stresses(c, k, sigma, tau);
      most = std::max({most, dem::utilisation(sigma, c.column[kTensileStrength][k]),
                       dem::utilisation(tau, c.column[kShearStrength][k])});
    }
    return most;
  }

 private:
  template <class Block>
  void stresses(const Block& c, std::size_t k, double& sigma, double& tau) const {
    const double rb = c.column[kBondRadius][k];
    const Section b = section_of(rb);
    const Vec3 fs{c.column[kBondFsX][k], c.column[kBondFsY][k], c.column[kBondFsZ][k]};
    const Vec3 mb{c.column[kBondMbX][k], c.column[kBondMbY][k], c.column[kBondMbZ][k]};
    sigma = -c.column[kBondFn][k] / b.area + beta_ * norm(mb) * rb / b.inertia;
    tau = norm(fs) / b.area + beta_ * std::abs(c.column[kBondMt][k]) * rb / b.polar;
  }

  // The block's pairs [from, from + n) in one vectorised loop, every pair
  // through the linear contact and the bond, the results picked by selects:
  //   - no bond: the linear contact while the spheres touch (distance below
  //     the radii summed), nothing otherwise;
  //   - a bond: the linear contact while they overlap, the bond's increments
  //     (j's motion relative to i's), its stresses from the stored values,
  //     and a break in tension or shear: the bond's columns cleared, the
  //     linear contact's force alone.
  // Flags: kTouching and kBonded here; a break's marks by the caller, from
  // `broke` and `tension`. Returns whether any bond broke.
  bool batch(PairBlock& c, const double* __restrict records, std::size_t from, std::size_t n, double dt_s,
             linear_batch::Batch& b,
             std::int32_t* __restrict broke_out, std::int32_t* __restrict tension_out) const {
    const std::int32_t* __restrict ci = c.i + from;
    const std::int32_t* __restrict cj = c.j + from;
    dem::PairFlags* __restrict flags = c.flags + from;
    const auto column = [&](std::size_t k) { return &c.column(k, from); };
    const double* __restrict kn = column(kKn);
    const double* __restrict ks = column(kKs);
    const double* __restrict friction = column(kFriction);
    const double* __restrict reference = column(kReferenceOverlap);
    double* __restrict shear_x = column(kShearX);
    double* __restrict shear_y = column(kShearY);
    double* __restrict shear_z = column(kShearZ);
    const double* __restrict bond_kn = column(kBondKn);
    const double* __restrict bond_ks = column(kBondKs);
    const double* __restrict bond_radius = column(kBondRadius);
    double* __restrict bond_fn_col = column(kBondFn);
    double* __restrict bond_fsx_col = column(kBondFsX);
    double* __restrict bond_fsy_col = column(kBondFsY);
    double* __restrict bond_fsz_col = column(kBondFsZ);
    double* __restrict bond_mt_col = column(kBondMt);
    double* __restrict bond_mbx_col = column(kBondMbX);
    double* __restrict bond_mby_col = column(kBondMbY);
    double* __restrict bond_mbz_col = column(kBondMbZ);
    const double* __restrict tensile = column(kTensileStrength);
    const double* __restrict shear_strength = column(kShearStrength);
    const double half_dt = 0.5 * dt_s, beta = beta_;
    using dem::select;
    unsigned any_broke = 0;
#pragma omp simd reduction(| : any_broke)
    for (std::size_t p = 0; p < n; ++p) {
      const linear_batch::SphereView i{records, kRecordSize * static_cast<std::size_t>(ci[p])};
      const linear_batch::SphereView j{records, kRecordSize * static_cast<std::size_t>(cj[p])};
      const bool has_bond = (flags[p] & dem::kBonded) != 0;
      const linear_batch::LaneGeometry g = linear_batch::lane_geometry(i, j);
      const linear_batch::LaneTurn turn = linear_batch::lane_turn(g, half_dt);
      const double nx = g.nx, ny = g.ny, nz = g.nz, overlap = g.overlap, arm_i = g.arm_i, arm_j = g.arm_j;
      const double rvx = g.rvx, rvy = g.rvy, rvz = g.rvz;
      // The linear contact (linear_shear_force), kept while the spheres touch.
      const bool touching = (has_bond & (overlap > 0)) | (!has_bond & (g.distance2 < g.reach * g.reach));  // & |: no branch
      const double squeeze = overlap - reference[p];
      const double fn_linear = kn[p] * select(0.0 < squeeze, squeeze, 0.0);
      double lx, ly, lz;
      linear_batch::lane_increment(g, turn, shear_x[p], shear_y[p], shear_z[p], rvx, rvy, rvz, ks[p] * dt_s, lx, ly,
                                   lz);
      const double limit = friction[p] * fn_linear, size2 = lx * lx + ly * ly + lz * lz;
      const double scale = select(size2 > limit * limit, limit / std::sqrt(size2), 1.0);
      const double fsx = select(touching, scale * lx, 0.0);
      const double fsy = select(touching, scale * ly, 0.0);
      const double fsz = select(touching, scale * lz, 0.0);
      const double fn = select(touching, fn_linear, 0.0);
      shear_x[p] = fsx, shear_y[p] = fsy, shear_z[p] = fsz;
      // The bond.
      const double rb = bond_radius[p], rb2 = rb * rb;
      const double area = M_PI * rb2, inertia = 0.25 * M_PI * rb2 * rb2, polar = 0.5 * M_PI * rb2 * rb2;
      const double kn_b = bond_kn[p], ks_b = bond_ks[p];
      const double rv_n = rvx * nx + rvy * ny + rvz * nz;
      const double bond_fn = bond_fn_col[p] - kn_b * area * rv_n * dt_s;
      double bfx, bfy, bfz;
      linear_batch::lane_increment(g, turn, bond_fsx_col[p], bond_fsy_col[p], bond_fsz_col[p], rvx, rvy, rvz,
                                   ks_b * area * dt_s, bfx, bfy, bfz);
      const double rsx = j.wx() - i.wx(), rsy = j.wy() - i.wy(), rsz = j.wz() - i.wz();
      const double bond_mt = bond_mt_col[p] + ks_b * polar * (rsx * nx + rsy * ny + rsz * nz) * dt_s;
      double bmx, bmy, bmz;
      linear_batch::lane_increment(g, turn, bond_mbx_col[p], bond_mby_col[p], bond_mbz_col[p], rsx, rsy, rsz,
                                   kn_b * inertia * dt_s, bmx, bmy, bmz);
      // stresses(): from the values as stored.
      const double mb_norm = std::sqrt(bmx * bmx + bmy * bmy + bmz * bmz);
      const double fs_norm = std::sqrt(bfx * bfx + bfy * bfy + bfz * bfz);
      const double sigma = -bond_fn / area + beta * mb_norm * rb / inertia;
      const double tau = fs_norm / area + beta * std::abs(bond_mt) * rb / polar;
      const bool tension = sigma >= tensile[p];
      const bool broke = has_bond & (tension | (tau >= shear_strength[p]));
      const bool holds = has_bond & !broke;
      bond_fn_col[p] = select(holds, bond_fn, select(broke, 0.0, bond_fn_col[p]));
      bond_fsx_col[p] = select(holds, bfx, select(broke, 0.0, bond_fsx_col[p]));
      bond_fsy_col[p] = select(holds, bfy, select(broke, 0.0, bond_fsy_col[p]));
      bond_fsz_col[p] = select(holds, bfz, select(broke, 0.0, bond_fsz_col[p]));
      bond_mt_col[p] = select(holds, bond_mt, select(broke, 0.0, bond_mt_col[p]));
      bond_mbx_col[p] = select(holds, bmx, select(broke, 0.0, bond_mbx_col[p]));
      bond_mby_col[p] = select(holds, bmy, select(broke, 0.0, bond_mby_col[p]));
      bond_mbz_col[p] = select(holds, bmz, select(broke, 0.0, bond_mbz_col[p]));
      const dem::PairFlags cleared = flags[p] & ~(dem::kTouching | dem::kBonded * static_cast<dem::PairFlags>(broke));
      flags[p] = cleared | dem::kTouching * static_cast<dem::PairFlags>(touching);
      broke_out[p] = broke;
      tension_out[p] = tension;
      any_broke |= broke;
      // The forces (set_contact_force; linear_touch for a pair without a bond).
      const double shx = fsx + select(holds, bfx, 0.0), shy = fsy + select(holds, bfy, 0.0),
                   shz = fsz + select(holds, bfz, 0.0);
      const double fn_sum = fn + select(holds, bond_fn, 0.0);
      const double force_x = select(holds, shx - fn_sum * nx, fsx - fn * nx);
      const double force_y = select(holds, shy - fn_sum * ny, fsy - fn * ny);
      const double force_z = select(holds, shz - fn_sum * nz, fsz - fn * nz);
      const double tx = select(holds, shx, fsx), ty = select(holds, shy, fsy), tz = select(holds, shz, fsz);
      const double ncx = ny * tz - nz * ty, ncy = nz * tx - nx * tz, ncz = nx * ty - ny * tx;
      const double ex = select(holds, bond_mt * nx + bmx, 0.0), ey = select(holds, bond_mt * ny + bmy, 0.0),
                   ez = select(holds, bond_mt * nz + bmz, 0.0);
      const double mix = arm_i * ncx, miy = arm_i * ncy, miz = arm_i * ncz;
      const double mjx = arm_j * ncx, mjy = arm_j * ncy, mjz = arm_j * ncz;
      const bool apart = !has_bond & !touching;
      b.fx[p] = select(apart, 0.0, force_x);
      b.fy[p] = select(apart, 0.0, force_y);
      b.fz[p] = select(apart, 0.0, force_z);
      b.mix[p] = select(apart, 0.0, select(has_bond, mix + ex, mix));
      b.miy[p] = select(apart, 0.0, select(has_bond, miy + ey, miy));
      b.miz[p] = select(apart, 0.0, select(has_bond, miz + ez, miz));
      b.mjx[p] = select(apart, 0.0, select(has_bond, mjx - ex, mjx));
      b.mjy[p] = select(apart, 0.0, select(has_bond, mjy - ey, mjy));
      b.mjz[p] = select(apart, 0.0, select(has_bond, mjz - ez, mjz));
    }
    return any_broke != 0;
  }

  double bond_modulus_pa_, bond_kn_ks_, lambda_;
  double sigma_c_, sigma_c_std_, tau_c_, tau_c_std_, beta_;
};

}  // namespace

void register_parallel_bond_model(ContactModelRegistry& registry) {
  registry.add("parallel_bond", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction", "bond_modulus_pa",
                                 "bond_kn_ks", "radius_multiplier", "tensile_strength_pa", "tensile_strength_std_pa",
                                 "shear_strength_pa", "shear_strength_std_pa", "moment_contribution"},
               [](const nlohmann::json& p, const std::string& where) {
                 return std::make_unique<ParallelBondModel>(p, where);
               });
  // PFC3D's linearpbond (pb_fa 0: this bond has no friction angle).
  registry.set_peer_names("parallel_bond", nlohmann::json::parse(R"({
    "pfc": {"model": "linearpbond",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "kn_n_m", "group": "property", "name": "kn"},
                   {"key": "ks_n_m", "group": "property", "name": "ks"},
                   {"key": "bond_modulus_pa", "group": "pb_deformability", "name": "emod"},
                   {"key": "bond_kn_ks", "group": "pb_deformability", "name": "kratio"},
                   {"key": "friction", "group": "property", "name": "fric"},
                   {"key": "tensile_strength_pa", "group": "property", "name": "pb_ten"},
                   {"key": "shear_strength_pa", "group": "property", "name": "pb_coh"},
                   {"group": "property", "name": "pb_fa", "value": 0},
                   {"key": "radius_multiplier", "group": "property", "name": "pb_rmul", "default": 1},
                   {"key": "moment_contribution", "group": "property", "name": "pb_mcf", "default": 1}]},
    "yade": {"model": "CohFrictMat", "notes": ["YADE sets its normal stiffness from young as 2 young R1 R2 / (R1 + R2) (PFC3D: pi min(R)^2 E / (R1 + R2)) and its cohesions over its own area: the same numbers make a stiffer or softer material there; check a YADE run against demcal's"],
      "keywords": [{"key": "modulus_pa", "name": "young"}, {"key": "kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "friction", "name": "frictionAngle", "as": "atan"},
                   {"key": "tensile_strength_pa", "name": "normalCohesion"},
                   {"key": "shear_strength_pa", "name": "shearCohesion"}, {"name": "isCohesive", "value": true}]}})"));
}

}  // namespace demcal::dem3d
