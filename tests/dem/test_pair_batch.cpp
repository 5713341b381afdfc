// The batched force laws (pair_batch.hpp) against the pair-by-pair laws they
// replaced, kept here as the reference: on pairs in every state a step meets
// (apart, touching, sliding, bonded, breaking in tension and in shear, glued
// across a gap), the same forces, moments, state, flags and break log, to the
// bit, in both of the loop's forms (sums into the disks, and per-pair results
// for the threaded sum).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demcal/core/rng.hpp"
#include "demcal/dem/bond_law.hpp"
#include "demcal/dem/contact_model.hpp"
#include "demcal/dem/linear_law.hpp"
#include "demcal/dem/pair_batch.hpp"

using namespace demcal::dem;

namespace {

// The models' own column indices (their enums are private to their files);
// each test checks the names against state_columns(), so a change there fails here.
enum ParallelBondColumn : std::size_t {
  kPbKn = kLinearColumns, kPbKs, kPbArea, kPbInertia, kPbRadius, kPbFn, kPbFs, kPbM, kPbTensile, kPbShear, kPbColumns
};
enum ContactBondColumn : std::size_t { kCbNormal = kLinearColumns, kCbShear, kCbColumns };

constexpr double kDt = 2e-8;
constexpr std::size_t kPairs = 300;  // several batches of 64 and a remainder

using ReferenceLaw = std::function<void(PairBlock&, Bodies&, const StepContext&)>;

// The pair-by-pair laws as they were before the batches (commit bd5296f).
void reference_linear(PairBlock& c, Bodies& b, const StepContext& step) {
  for_disk_pairs(c, b, step, [&](std::size_t k, const Geometry& g) { return linear_force(c, k, g, step.dt_s); },
                 [&](std::size_t k, double gap) { return skip_apart(c, k, gap); });
}

void reference_parallel_bond(PairBlock& c, Bodies& b, const StepContext& step) {
  const double dt = step.dt_s;
  for_disk_pairs(
      c, b, step,
      [&](std::size_t k, const Geometry& g) {
        PairForce f = linear_force(c, k, g, dt);
        if (!(c.flags[k] & kBonded)) return f;
        const PairState<double> s = c.column.pair(k);
        const double area = s[kPbArea], inertia = s[kPbInertia];
        s[kPbFn] -= s[kPbKn] * area * g.vn * dt;
        s[kPbFs] -= s[kPbKs] * area * g.vs * dt;
        s[kPbM] -= s[kPbKn] * inertia * g.relative_w * dt;
        const double sigma_ai = -s[kPbFn] * inertia + std::abs(s[kPbM]) * s[kPbRadius] * area;
        const double tau_a = std::abs(s[kPbFs]);
        const bool tension = sigma_ai >= s[kPbTensile] * area * inertia;
        if (tension || tau_a >= s[kPbShear] * area) {
          break_bond(c, k, g, b, step, tension ? BreakMode::Tension : BreakMode::Shear);
          s[kPbFn] = s[kPbFs] = s[kPbM] = 0.0;
          return f;
        }
        f.fn += s[kPbFn];
        f.fs += s[kPbFs];
        f.moment = s[kPbM];
        return f;
      },
      [&](std::size_t k, double gap) { return skip_unbonded_apart(c, k, gap); });
}

void reference_contact_bond(PairBlock& c, Bodies& b, const StepContext& step) {
  const double dt = step.dt_s;
  for_disk_pairs(
      c, b, step,
      [&](std::size_t k, const Geometry& g) {
        if (!(c.flags[k] & kBonded)) return linear_force(c, k, g, dt);
        const PairState<double> s = c.column.pair(k);
        PairForce f;
        f.fn = s[kNormalStiffness] * (g.overlap - s[kReferenceOverlap]);
        s[kShearForce] -= s[kShearStiffness] * g.vs * dt;
        f.fs = s[kShearForce];
        if (-f.fn >= s[kCbNormal]) {
          break_bond(c, k, g, b, step, BreakMode::Tension);
          release(c, k);
          return PairForce{};
        }
        if (std::abs(f.fs) >= s[kCbShear]) {
          break_bond(c, k, g, b, step, BreakMode::Shear);
          if (f.fn <= 0) {
            release(c, k);
            return PairForce{};
          }
          c.flags[k] |= kTouching;
          return f;
        }
        c.flags[k] = static_cast<std::uint8_t>(g.overlap > 0 ? (c.flags[k] | kTouching) : (c.flags[k] & ~kTouching));
        return f;
      },
      [&](std::size_t k, double gap) { return skip_unbonded_apart(c, k, gap); });
}

struct Case {
  Bodies bodies;
  ContactSet pairs;
};

// Half the pairs are two disks of their own 30 um either side of touching
// (so a reference overlap from genesis decides whether they touch), the other
// half join disks of the first half at random (mostly far apart, and sharing
// disks, so the sums' order counts). Random motion; random state in every
// column, with bond forces of the order of their strengths so some break in
// each mode. With apart, every pair stands apart by its distance (the first
// half by up to 30 um, where a glued gap still makes some touch) and the
// random half has no glued gaps, so whole batches of it stand apart for the
// linear model's shortcut.
Case random_case(std::uint64_t seed, std::size_t columns, const std::string& model, bool apart = false) {
  demcal::Rng rng(seed);
  Case c;
  for (std::size_t k = 0; k < kPairs / 2; ++k) {
    const double ri = rng.uniform(4e-4, 6e-4), rj = rng.uniform(4e-4, 6e-4);
    const double xi = rng.uniform(0, 0.02), yi = rng.uniform(0, 0.02), angle = rng.uniform(0, 2 * M_PI);
    const double distance = ri + rj - rng.uniform(-3e-5, apart ? -1e-7 : 3e-5);
    c.bodies.add_disk(xi, yi, ri, 2650, 1.0, 0);
    c.bodies.add_disk(xi + distance * std::cos(angle), yi + distance * std::sin(angle), rj, 2650, 1.0, 1);
  }
  const std::size_t disks = c.bodies.size();
  for (std::size_t d = 0; d < disks; ++d) {
    c.bodies.vx[d] = rng.uniform(-1, 1);
    c.bodies.vy[d] = rng.uniform(-1, 1);
    c.bodies.w[d] = rng.uniform(-2e3, 2e3);
  }
  // Sums that already hold the forces of other models (never -0, as sums that start at +0).
  for (std::size_t d = 0; d < disks; ++d) {
    c.bodies.fx[d] = rng.uniform(-1, 1);
    c.bodies.fy[d] = rng.uniform(-1, 1);
    c.bodies.moment[d] = rng.uniform(-1e-3, 1e-3);
  }
  c.pairs.set_layout({columns});
  for (std::size_t k = 0; k < kPairs / 2; ++k)
    c.pairs.add(static_cast<std::int32_t>(2 * k), static_cast<std::int32_t>(2 * k + 1), 0);
  for (std::size_t k = kPairs / 2; k < kPairs; ++k) {
    const auto i = static_cast<std::int32_t>(rng.below(disks - 1));
    const auto j = static_cast<std::int32_t>(i + 1 + static_cast<std::int32_t>(rng.below(disks - 1 - i)));
    c.pairs.add(i, j, 0);
  }
  PairBlock block = c.pairs.block(0);
  for (std::size_t k = 0; k < kPairs; ++k) {
    const PairState<double> s = block.column.pair(k);
    s[kNormalStiffness] = rng.uniform(1e6, 1e8);
    s[kShearStiffness] = s[kNormalStiffness] / rng.uniform(1, 3);
    s[kFriction] = rng.uniform(0, 1);
    s[kShearForce] = rng.uniform(-5, 5);
    // Genesis's reference overlaps: zero, an overlap kept, or a gap glued.
    const double kind = rng.uniform();
    s[kReferenceOverlap] = kind < 0.4 ? 0.0 : rng.uniform(apart && k >= kPairs / 2 ? 0.0 : -2e-5, 2e-5);
    const bool bonded = rng.uniform() < 0.7;
    block.flags[k] = (bonded ? kBonded : 0u) | (rng.uniform() < 0.5 ? kTouching : 0u);
    if (model == "parallel_bond") {
      const double rb = rng.uniform(4e-4, 6e-4);
      s[kPbKn] = rng.uniform(1e12, 1e13);
      s[kPbKs] = s[kPbKn] / rng.uniform(1, 3);
      s[kPbArea] = 2 * rb;
      s[kPbInertia] = 2.0 / 3.0 * rb * rb * rb;
      s[kPbRadius] = rb;
      s[kPbTensile] = rng.uniform(1e6, 2e7);
      s[kPbShear] = rng.uniform(1e6, 4e7);
      // Forces up to about twice what the strengths allow.
      s[kPbFn] = bonded ? rng.uniform(-2, 1) * s[kPbTensile] * s[kPbArea] : 0.0;
      s[kPbFs] = bonded ? rng.uniform(-1.5, 1.5) * s[kPbShear] * s[kPbArea] : 0.0;
      s[kPbM] = bonded ? rng.uniform(-0.5, 0.5) * s[kPbTensile] * s[kPbInertia] / rb : 0.0;
    } else if (model == "contact_bond") {
      // Tensile strengths up to the force of 30 um of pull; shear strengths
      // about the shear forces drawn above.
      s[kCbNormal] = rng.uniform(0, 3e-5) * s[kNormalStiffness];
      s[kCbShear] = rng.uniform(0.5, 8);
    }
  }
  return c;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

struct Counts {
  std::size_t skipped = 0, tension = 0, shear = 0;
  std::size_t touching = 0;  // pairs touching after the step (the reference's flags)
};

// Runs the model's batched law and the reference on copies of one case, in
// both forms, and compares everything they wrote.
Counts check(const std::string& model_name, const nlohmann::json& parameters, std::size_t columns,
             const ReferenceLaw& reference, std::uint64_t seed, bool apart = false) {
  const auto model = ContactModelRegistry::instance().create(model_name, parameters, "test");
  EXPECT_EQ(model->state_columns().size(), columns);
  Counts counts;
  // The three forms: forces to the disks (one thread), every pair's result
  // stored, and the threaded step's form (results stored and forces added to
  // the disks a random mask names).
  enum Form { kToDisks, kResults, kResultsAndDirect };
  for (const Form form : {kToDisks, kResults, kResultsAndDirect}) {
    const bool keep_results = form != kToDisks;
    const Case base = random_case(seed, columns, model_name, apart);
    Case batched = base, pairwise = base;
    std::vector<BreakEvent> batched_log, pairwise_log;
    // Stored results from an earlier step, which every pair the law writes must replace.
    std::vector<PairResult> batched_results(kPairs, PairResult{7.0, -7.0, 1e-3, -1e-3});
    std::vector<PairResult> pairwise_results = batched_results;
    std::vector<std::uint8_t> direct(kPairs);
    demcal::Rng mask_rng(seed + 1000);
    for (std::uint8_t& d : direct) d = static_cast<std::uint8_t>(mask_rng.uniform() < 0.7 ? kAddToBoth : mask_rng.below(3));
    StepContext batched_step{kDt, 1e-3, 1.0, &batched_log, keep_results ? batched_results.data() : nullptr,
                             form == kResultsAndDirect ? direct.data() : nullptr};
    StepContext pairwise_step{kDt, 1e-3, 1.0, &pairwise_log, keep_results ? pairwise_results.data() : nullptr,
                              form == kResultsAndDirect ? direct.data() : nullptr};
    PairBlock batched_block = batched.pairs.block(0), pairwise_block = pairwise.pairs.block(0);
    model->disk_forces(batched_block, batched.bodies, batched_step);
    reference(pairwise_block, pairwise.bodies, pairwise_step);

    EXPECT_TRUE(same_bits(batched.bodies.fx, pairwise.bodies.fx)) << model_name << " seed " << seed;
    EXPECT_TRUE(same_bits(batched.bodies.fy, pairwise.bodies.fy)) << model_name << " seed " << seed;
    EXPECT_TRUE(same_bits(batched.bodies.moment, pairwise.bodies.moment)) << model_name << " seed " << seed;
    if (keep_results) {
      EXPECT_EQ(std::memcmp(batched_results.data(), pairwise_results.data(), kPairs * sizeof(PairResult)), 0)
          << model_name << " seed " << seed;
    }
    const ConstPairBlock before = base.pairs.block(0);
    for (std::size_t k = 0; k < kPairs; ++k) {
      EXPECT_EQ(batched_block.flags[k], pairwise_block.flags[k]) << model_name << " pair " << k;
      for (std::size_t col = 0; col < columns; ++col)
        EXPECT_EQ(std::memcmp(&batched_block.column[col][k], &pairwise_block.column[col][k], sizeof(double)), 0)
            << model_name << " pair " << k << " column " << col << " seed " << seed;
      if (!(before.flags[k] & kBonded) && !(pairwise_block.flags[k] & kTouching)) ++counts.skipped;
      if (form == kToDisks && (pairwise_block.flags[k] & kTouching)) ++counts.touching;
    }
    EXPECT_EQ(batched_log.size(), pairwise_log.size()) << model_name << " seed " << seed;
    if (batched_log.size() != pairwise_log.size()) return counts;
    for (std::size_t e = 0; e < pairwise_log.size(); ++e) {
      EXPECT_EQ(std::memcmp(&batched_log[e].x_m, &pairwise_log[e].x_m, sizeof(double)), 0);
      EXPECT_EQ(std::memcmp(&batched_log[e].y_m, &pairwise_log[e].y_m, sizeof(double)), 0);
      EXPECT_EQ(batched_log[e].time_s, pairwise_log[e].time_s);
      EXPECT_EQ(batched_log[e].mode, pairwise_log[e].mode);
      EXPECT_EQ(batched_log[e].group_i, pairwise_log[e].group_i);
      EXPECT_EQ(batched_log[e].group_j, pairwise_log[e].group_j);
      if (form == kToDisks) ++(pairwise_log[e].mode == BreakMode::Tension ? counts.tension : counts.shear);
    }
  }
  return counts;
}

// check() over seeds 1-5, the counts summed.
Counts check_seeds(const std::string& model_name, const nlohmann::json& parameters, std::size_t columns,
                   const ReferenceLaw& reference, bool apart = false) {
  Counts all;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Counts c = check(model_name, parameters, columns, reference, seed, apart);
    all.skipped += c.skipped;
    all.tension += c.tension;
    all.shear += c.shear;
    all.touching += c.touching;
  }
  return all;
}

}  // namespace

TEST(PairBatch, LinearModelGivesThePairByPairBits) {
  const nlohmann::json p = {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}};
  EXPECT_GT(check_seeds("linear", p, kLinearColumns, reference_linear).skipped, 50u);  // pairs apart are part of the comparison
}

// The linear model releases a batch whose pairs all stand apart without its
// geometry (linear_model.cpp): the same state, flags, sums and stored results;
// a batch apart by distance with a glued gap among its pairs takes the law.
TEST(PairBatch, LinearModelReleasesBatchesApartWithThePairByPairBits) {
  const nlohmann::json p = {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}};
  // The premise: some of the cases' batches stand apart, so the shortcut runs.
  std::size_t apart_batches = 0, batches = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    Case c = random_case(seed, kLinearColumns, "linear", true);
    const PairBlock block = c.pairs.block(0);
    for (std::size_t from = 0; from < block.size; from += kPairBatch, ++batches)
      apart_batches += batch_stands_apart(block, c.bodies, from, std::min(kPairBatch, block.size - from));
  }
  EXPECT_GE(apart_batches, 15u) << "of " << batches;  // 21 of 25
  // ... and some of their pairs touch through a glued gap (76).
  EXPECT_GT(check_seeds("linear", p, kLinearColumns, reference_linear, true).touching, 50u);
}

// batch_stands_apart: true only when every pair's squared distance clears
// (r_i + r_j)^2 by more than rounding; a pair that touches exactly, or misses
// by a relative 1e-12, keeps its batch in the law.
TEST(PairBatch, BatchStandsApartOnlyWhenEveryPairClearsItsReach) {
  Bodies b;
  ContactSet pairs;
  pairs.set_layout({kLinearColumns});
  const double r = 5e-4;
  // Pair k: disks 2k and 2k+1 on a row, 1 % of their reach apart.
  for (std::size_t k = 0; k < kPairBatch; ++k) {
    const double x = 0.01 * static_cast<double>(k);
    b.add_disk(x, 0.0, r, 2650, 1.0, 0);
    b.add_disk(x + 2 * r * 1.01, 0.0, r, 2650, 1.0, 0);
    pairs.add(static_cast<std::int32_t>(2 * k), static_cast<std::int32_t>(2 * k + 1), 0);
  }
  const PairBlock c = pairs.block(0);
  EXPECT_TRUE(batch_stands_apart(c, b, 0, kPairBatch));
  EXPECT_TRUE(batch_stands_apart(c, b, 0, 5));  // a short batch
  for (const std::size_t k : {std::size_t{0}, std::size_t{9}, kPairBatch - 1}) {
    for (const double gap : {0.0, 1e-12, -1e-6}) {  // exact contact, within rounding, overlapping
      const double saved = b.x[2 * k + 1];
      b.x[2 * k + 1] = b.x[2 * k] + 2 * r * (1 + gap);
      EXPECT_FALSE(batch_stands_apart(c, b, 0, kPairBatch)) << "pair " << k << " gap " << gap;
      b.x[2 * k + 1] = saved;
    }
  }
  // Pairs past the batch's end do not count.
  b.x[2 * 6 + 1] = b.x[2 * 6];
  EXPECT_TRUE(batch_stands_apart(c, b, 0, 6));
  EXPECT_FALSE(batch_stands_apart(c, b, 0, 7));
}

TEST(PairBatch, ParallelBondGivesThePairByPairBitsAndBreaks) {
  const nlohmann::json p = {{"modulus_pa", 1e9},         {"kn_ks", 2.0},         {"friction", 0.5},
                            {"bond_modulus_pa", 1e9},    {"bond_kn_ks", 2.0},    {"tensile_strength_pa", 1e7},
                            {"shear_strength_pa", 2e7}};
  const auto model = ContactModelRegistry::instance().create("parallel_bond", p, "test");
  const std::vector<std::string> names = model->state_columns();
  ASSERT_EQ(names.size(), kPbColumns);
  EXPECT_EQ(names[kPbKn], "bond_kn_pa_m");
  EXPECT_EQ(names[kPbFn], "bond_normal_force_n");
  EXPECT_EQ(names[kPbM], "bond_moment_nm");
  EXPECT_EQ(names[kPbShear], "bond_shear_strength_pa");
  const Counts all = check_seeds("parallel_bond", p, kPbColumns, reference_parallel_bond);
  EXPECT_GT(all.skipped, 10u);
  EXPECT_GT(all.tension, 20u);
  EXPECT_GT(all.shear, 20u);
}

TEST(PairBatch, ContactBondGivesThePairByPairBitsAndBreaks) {
  const nlohmann::json p = {{"modulus_pa", 1e9}, {"kn_ks", 2.0}, {"friction", 0.5}, {"tensile_strength_pa", 1e7},
                            {"shear_strength_pa", 2e7}};
  const auto model = ContactModelRegistry::instance().create("contact_bond", p, "test");
  const std::vector<std::string> names = model->state_columns();
  ASSERT_EQ(names.size(), kCbColumns);
  EXPECT_EQ(names[kCbNormal], "bond_normal_strength_n");
  EXPECT_EQ(names[kCbShear], "bond_shear_strength_n");
  const Counts all = check_seeds("contact_bond", p, kCbColumns, reference_contact_bond);
  EXPECT_GT(all.skipped, 10u);
  EXPECT_GT(all.tension, 20u);
  EXPECT_GT(all.shear, 20u);
}
