// The exact scaling of quasi-static bonded DEM, which a dimensionless
// calibration rests on. Multiply every stress-like parameter (by its unit:
// moduli, stiffnesses, strengths) by k: forces at a given deformation grow by
// k, masses do not, so the motion runs sqrt(k) times faster and the computed
// time step shrinks by sqrt(k). With the platen velocity also multiplied by
// sqrt(k) the run is the same run in scaled time: stresses times k, strains,
// nu and crack counts unchanged. At the same platen velocity (what a user
// does) only the loading rate relative to the specimen's own time changes;
// local damping is proportional to force and does not break the scaling.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "demcal/core/units.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"

using namespace demcal;
using namespace demcal::dem;

namespace {

nlohmann::json scene_json(const std::string& file) {
  std::ifstream in(std::string(DEMCAL_SOURCE_DIR) + "/tests/data/" + file);
  return nlohmann::json::parse(in);
}

// The scene with every stress-like parameter's default times k (bounds opened
// to fit) and the platen velocity times velocity_factor.
Scene scaled_scene(nlohmann::json j, double k, double velocity_factor) {
  for (auto& [name, p] : j.at("parameters").items())
    if (is_stress_like(quantity_of_unit(p.at("unit").get<std::string>(), name))) {
      p["value"] = k * p.at("value").get<double>();
      p["high"] = 1e300;
    }
  j["loading"]["platen_velocity_m_s"] = velocity_factor * j.at("loading").at("platen_velocity_m_s").get<double>();
  return Scene::from_json(j, "scaled.json");
}

bool stress_output(const Scene& scene, const std::string& name) {
  for (const OutputSpec& o : scene.lab_test().outputs(scene))
    if (o.name == name) return is_stress_like(quantity_of_unit(o.unit, name));
  ADD_FAILURE() << "no output " << name;
  return false;
}

TestResult run(const Scene& scene, std::uint64_t seed) {
  RunOptions options;
  options.seed = seed;
  TestResult r = run_test(scene, scene.resolve({}), options);
  EXPECT_TRUE(r.ok) << r.reason;
  return r;
}

// k = 4, velocity x 2: every product and quotient of the run is scaled by a
// power of two, so the outputs are the same bits (stresses times 4).
void expect_bit_exact_scaling(const std::string& file) {
  const nlohmann::json j = scene_json(file);
  const Scene base = scaled_scene(j, 1.0, 1.0), scaled = scaled_scene(j, 4.0, 2.0);
  const TestResult a = run(base, 1), b = run(scaled, 1);
  ASSERT_EQ(a.macro.size(), b.macro.size());
  for (const auto& [name, value] : a.macro) {
    const double factor = stress_output(base, name) ? 4.0 : 1.0;
    EXPECT_EQ(b.macro.at(name), factor * value) << file << ": " << name;
  }
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(b.dt_s, 0.5 * a.dt_s);
}

TEST(ExactScaling, StressParametersTimesFourAndVelocityTimesTwoGiveTheSameRun) {
  expect_bit_exact_scaling("ucs_rock_cb_small.json");  // contact bonds with random strengths
  expect_bit_exact_scaling("ucs_small.json");          // parallel bonds
}

TEST(ExactScaling, AtTheSamePlatenVelocityTheOutputsStayWithinTheSeedNoise) {
  // Common specimens (seeds 1-6) at k = 1, 2 and 10. The run is then
  // sqrt(k) times slower relative to the specimen's wave time, which moves
  // the outputs by far less than the seed-to-seed scatter. Measured on this
  // scene (2026-12-02, platens starting at the vessel faces), mean paired
  // shifts over the seeds 1-6 asserted here: sigma_u +0.9 % (k = 2) and
  // -1.2 % (k = 10), E -0.1 % and +0.2 %, nu -2.0 % and +0.6 %; seed-to-seed
  // CV over seeds 1-8: 18 %, 4 % and 22 %. One specimen moves far more
  // (seed 3: nu -11 % at k = 2, a different crack path), so four seeds were
  // too few to average it out.
  const nlohmann::json j = scene_json("ucs_rock_cb_small.json");
  const Scene base = scaled_scene(j, 1.0, 1.0);
  const int seeds = 6;
  std::vector<TestResult> reference;
  for (int s = 1; s <= seeds; ++s) reference.push_back(run(base, s));
  for (double k : {2.0, 10.0}) {
    const Scene scaled = scaled_scene(j, k, 1.0);
    std::map<std::string, double> shift_pct;
    for (int s = 1; s <= seeds; ++s) {
      const TestResult r = run(scaled, s);
      for (const char* name : {"sigma_u_MPa", "E_GPa", "nu"}) {
        const double factor = stress_output(base, name) ? k : 1.0;
        shift_pct[name] += 100.0 * (r.macro.at(name) / factor / reference[s - 1].macro.at(name) - 1.0) / seeds;
      }
    }
    for (const auto& [name, shift] : shift_pct) {
      double mean = 0, ss = 0;
      for (const TestResult& r : reference) mean += r.macro.at(name) / seeds;
      for (const TestResult& r : reference) ss += std::pow(r.macro.at(name) - mean, 2);
      const double standard_error_pct = 100.0 * std::sqrt(ss / (seeds - 1)) / std::sqrt(double(seeds)) / mean;
      EXPECT_LT(std::fabs(shift), standard_error_pct) << name << " at k = " << k;  // within the noise of a 6-seed mean
      EXPECT_LT(std::fabs(shift), 3.0) << name << " at k = " << k;
    }
  }
}

}  // namespace
