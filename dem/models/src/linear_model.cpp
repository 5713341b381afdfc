// Linear contact model: stiffness by the deformability method, Coulomb friction.
//   parameters: {"modulus_pa": E_c, "kn_ks": kn/ks, "friction": mu}
//   state: the linear columns only (kn_n_m, ks_n_m, friction, shear_force_n,
//   reference_overlap_m).

#include <nlohmann/json.hpp>

#include "demcal/dem/builtin_models.hpp"
#include "demcal/dem/linear_base.hpp"
#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/model_parameters.hpp"
#include "demcal/dem/pair_batch.hpp"

namespace demcal::dem {
namespace {

class LinearModel : public LinearBase {
 public:
  LinearModel(const nlohmann::json& p, const std::string& where) : LinearBase(p, where, true) {
  }
  std::string name() const override { return "linear"; }

  // Batches of pairs, each one vectorised loop (pair_batch.hpp), with
  // linear_force's arithmetic: the same bits as pair by pair. A pair apart is
  // skipped as skip_apart skips it: no force, no shear, and nothing added to
  // its disks (many listed pairs stand apart in a loose packing). A batch
  // whose pairs all stand apart is released without its geometry (no square
  // roots): the same state, flags and (zero) forces as through the law.
  void disk_forces(PairBlock& c, Bodies& b, const StepContext& step) const override {
    for_pair_batches</*kSkipZero=*/true>(
        c, b, step,
        [&](std::size_t from, std::size_t n, const GeometryBatch& g, ForceBatch& f) {
          law(c, from, n, g, f, step.dt_s);
        },
        [&](std::size_t from, std::size_t n) { return release_if_apart(c, b, from, n, step); });
  }

 private:
  // A pair apart by distance is apart for the law when its reference overlap
  // is >= 0 (overlap - reference <= 0); a negative reference (a gap that
  // genesis bonded) takes the law.
  static bool release_if_apart(const PairBlock& c, const Bodies& b, std::size_t from, std::size_t n,
                               const StepContext& step) {
    if (!batch_stands_apart(c, b, from, n)) return false;
    const double* __restrict reference = &c.column[kReferenceOverlap][from];
    unsigned gap = 0;
    for (std::size_t p = 0; p < n; ++p) gap |= static_cast<unsigned>(!(reference[p] >= 0));
    if (gap) return false;
    for (std::size_t p = 0; p < n; ++p) release(c, from + p);
    store_zero_results(step, from, n);
    return true;
  }

  static void law(const PairBlock& c, std::size_t from, std::size_t n, const GeometryBatch& __restrict g,
                  ForceBatch& __restrict f, double dt) {
    const StateColumns<double> s = c.column.from(from);
    const PairFlags* __restrict flags = c.flags + from;
#pragma omp simd
    for (std::size_t p = 0; p < n; ++p) {
      const LinearLane lin = linear_lane(s, p, g.overlap[p], g.vs[p], dt);
      s(kShearForce, p) = select(!lin.touching, 0.0, lin.fs);
      batch_force(f, p, g, !lin.touching, lin.fn, lin.fs, 0.0);
      f.flags[p] = (flags[p] & ~static_cast<PairFlags>(kTouching)) |
                   (lin.touching ? static_cast<PairFlags>(kTouching) : 0u);
      f.broke[p] = 0u;
      f.tension[p] = 0u;
    }
  }
};

}  // namespace

void register_linear_model(ContactModelRegistry& registry) {
  registry.add("linear", {"modulus_pa", "kn_ks", "kn_n_m", "ks_n_m", "friction"}, [](const nlohmann::json& p, const std::string& where) {
    return std::make_unique<LinearModel>(p, where);
  });
  // PFC's linear model by the deformability method (or its kn and ks); YADE's
  // FrictMat takes poisson as ks / kn; LIGGGHTS has Hertz-Mindlin, not springs.
  registry.set_peer_names("linear", nlohmann::json::parse(R"({
    "pfc": {"model": "linear",
      "keywords": [{"key": "modulus_pa", "group": "deformability", "name": "emod"},
                   {"key": "kn_ks", "group": "deformability", "name": "kratio"},
                   {"key": "kn_n_m", "group": "property", "name": "kn"},
                   {"key": "ks_n_m", "group": "property", "name": "ks"},
                   {"key": "friction", "group": "property", "name": "fric"}]},
    "yade": {"model": "FrictMat",
      "keywords": [{"key": "modulus_pa", "name": "young"}, {"key": "kn_ks", "name": "poisson", "as": "reciprocal"},
                   {"key": "friction", "name": "frictionAngle", "as": "atan"}]},
    "liggghts": {"model": "hertz", "notes": [],
      "keywords": [{"key": "modulus_pa", "name": "youngsModulus"},
                   {"key": "kn_ks", "name": "poissonsRatio", "as": "hertz_mindlin_poisson"},
                   {"key": "friction", "name": "coefficientFriction", "per": "pair"}]}})"));
}

}  // namespace demcal::dem
