// The slope section and its test (slope_specimen.hpp, slope_test.hpp): the
// profiles' arithmetic against hand values, the section's parts meeting
// without overlap inside their regions, and the test on a small slope: the
// boundaries hold it where the walls did, the pulse reaches the points in
// the order of their distance from the input, the viscous boundaries quiet
// the slope far sooner than fixed ones, and bad input fails in one line
// naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/dem/ground_motion.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/slope_specimen.hpp"
#include "demcal/dem/slope_test.hpp"

using namespace demcal::dem;
using json = nlohmann::json;

namespace {

const std::string kScene = std::string(DEMCAL_SOURCE_DIR) + "/tests/data/slope_small.json";

Scene patched(const json& patch) {
  json scene = Scene::resolved_json(kScene);
  scene.merge_patch(patch);
  return Scene::from_json(scene, "slope_small (patched)");
}

TestResult run_patched(const json& patch) {
  const Scene s = patched(patch);
  RunOptions options;
  options.seed = 1;
  return run_test(s, s.resolve({}), options);
}

std::string error_of(const json& patch) {
  try {
    const Scene s = patched(patch);
    RunOptions options;
    options.seed = 1;
    run_test(s, s.resolve({}), options);
  } catch (const demcal::Error& e) {
    return e.what();
  }
  return "";
}

// A file in the test's temporary folder with `text`; returns its path.
std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(SlopeProfile, InterpolatesBoundsAndIntegratesAsByHand) {
  Profile p;
  p.x = {0, 10, 30};
  p.y = {5, 5, 15};
  EXPECT_DOUBLE_EQ(p.at(-1), 5);
  EXPECT_DOUBLE_EQ(p.at(20), 10);
  EXPECT_DOUBLE_EQ(p.at(40), 15);
  EXPECT_DOUBLE_EQ(p.min_y(5, 25), 5);
  EXPECT_DOUBLE_EQ(p.max_y(5, 25), 12.5);
  EXPECT_DOUBLE_EQ(p.area_above(0), 10 * 5 + 20 * 10);  // a rectangle and a trapezoid
  EXPECT_DOUBLE_EQ(p.area_above(10), 20 * 5 / 2.0);     // only the triangle above y = 10
  p.x = {0, 10, 8};
  try {
    p.validate("s.json: slope.bedrock.surface");
    FAIL() << "a profile turning back on itself was taken";
  } catch (const demcal::Error& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: slope.bedrock.surface[2]: x 8 m does not exceed"), std::string::npos)
        << e.what();
  }
}

TEST(SlopeSpecimen, PartsMeetWithoutOverlapInsideTheirRegions) {
  SlopeSpec spec;
  spec.width_m = 60;
  spec.height_m = 40;
  spec.bedrock = {"bedrock", 1.0, 1.25, 0.16, 2600};
  spec.bedrock_surface.x = {0, 20, 60};
  spec.bedrock_surface.y = {25, 25, 12};
  SlopeZone fill;
  fill.part = {"fill", 0.3, 0.45, 0.16, 2000};
  fill.top.x = {0, 20, 35};
  fill.top.y = {29, 29, 21};
  spec.zones = {fill};
  spec.column_width_m = 10;
  spec.seed = 3;
  const SlopeSpecimen s = build_slope_specimen(spec, "");
  ASSERT_EQ(s.part_disks.size(), 2u);
  EXPECT_GT(s.part_disks[0], 150u);
  EXPECT_GT(s.part_disks[1], 80u);
  for (std::size_t i = 0; i < s.size(); ++i) {
    // Inside the model, but for the few per cent of a radius a packing's disks press into its vessel.
    EXPECT_GE(s.x[i] - s.radius[i], -0.05 * s.radius[i]);
    EXPECT_LE(s.x[i] + s.radius[i], spec.width_m + 0.05 * s.radius[i]);
    EXPECT_GE(s.y[i] - s.radius[i], -0.05 * s.radius[i]);
    // Each disk wholly below its part's top.
    const double top = s.part[i] == 0 ? spec.bedrock_surface.at(s.x[i]) : fill.top.at(s.x[i]);
    EXPECT_LE(s.y[i] + s.radius[i], top + 1e-9) << "disk " << i;
  }
  // No fill disk overlaps a bedrock disk (they keep their own packing's overlaps among themselves).
  std::size_t crossings = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = 0; j < s.size(); ++j)
      if (s.part[i] == 1 && s.part[j] == 0 && std::hypot(s.x[i] - s.x[j], s.y[i] - s.y[j]) < s.radius[i] + s.radius[j])
        ++crossings;
  EXPECT_EQ(crossings, 0u);
  // The bedrock's region: below the surface, 25 x 20 + (25 + 12) / 2 x 40.
  EXPECT_DOUBLE_EQ(s.part_area_m2[0], 25 * 20 + 0.5 * (25 + 12) * 40);
  // The same seed gives the same section.
  const SlopeSpecimen again = build_slope_specimen(spec, "");
  EXPECT_EQ(again.x, s.x);
  EXPECT_EQ(again.radius, s.radius);
}

TEST(Slope, TheBoundariesHoldItAndThePulseRisesThroughTheBedrock) {
  const TestResult r = run_patched(json::object());
  ASSERT_TRUE(r.ok) << r.reason;
  // The walls' static load passes to the boundaries: over the quiet period nothing moves by more than a few
  // per cent of a bedrock radius, and the bedrock stays at rest.
  EXPECT_LT(r.macro.at("quiet_drift_m"), 0.1);
  EXPECT_LT(r.macro.at("quiet_force_ratio"), 1e-3);
  // A P and S pulse in at the bottom: the point 5 m up peaks before the one 25 m up.
  EXPECT_LT(r.macro.at("peak_time_s_1_1"), r.macro.at("peak_time_s_1_2"));
  // The slope carries the pulse (0.2 m/s each in P and S: up to 0.28 m/s together, and twice that at the free surface).
  EXPECT_GT(r.specimen_info.at("carried_peak_speed_m_s"), 0.1);
  EXPECT_LT(r.specimen_info.at("carried_peak_speed_m_s"), 0.6);
  // The objective: the three points it names.
  EXPECT_DOUBLE_EQ(r.macro.at("total_recovery_time_s"),
                   r.macro.at("recovery_time_s_1_1") + r.macro.at("recovery_time_s_2_1") + r.macro.at("recovery_time_s_3_1"));
  // The dashpots take out most of what came in.
  EXPECT_GT(r.macro.at("energy_absorbed_J"), 0.5 * r.macro.at("energy_input_J"));
  // The deposit has not moved off (a pulse of 0.2 m/s).
  EXPECT_NEAR(r.macro.at("deposit_left_end_m"), r.macro.at("deposit_left_start_m"), 0.5);
  EXPECT_NEAR(r.macro.at("deposit_right_end_m"), r.macro.at("deposit_right_start_m"), 0.5);
  // Tributary-by-radius dashpots stand for each side's whole length.
  for (const char* side : {"bottom", "left", "right"})
    EXPECT_NEAR(r.specimen_info.at(std::string("dashpot_coverage_") + side), 1.0, 1e-9) << side;
}

TEST(Slope, ARestStateFromTheCacheGivesTheSameBitsAsComingToRest) {
  const std::string cache = ::testing::TempDir() + "slope_rest_cache";
  std::filesystem::remove_all(cache);
  const Scene s = patched(json::object());
  RunOptions options;
  options.seed = 1;
  options.cache_dir = cache;
  const TestResult first = run_test(s, s.resolve({}), options);  // comes to rest and keeps it
  const TestResult again = run_test(s, s.resolve({}), options);  // reads it back
  RunOptions uncached = options;
  uncached.cache_dir = "";
  const TestResult plain = run_test(s, s.resolve({}), uncached);
  ASSERT_TRUE(first.ok && again.ok && plain.ok);
  EXPECT_EQ(first.macro, again.macro);
  EXPECT_EQ(first.macro, plain.macro);
  EXPECT_EQ(first.series, again.series);
  EXPECT_EQ(first.specimen_info, again.specimen_info);
  // Other boundaries share the rest (it does not depend on them); another friction does not.
  std::size_t rests = 0;
  const Scene softer = patched(json::parse(R"({"parameters": {"xi_left": {"value": 1.5}}})"));
  run_test(softer, softer.resolve({}), options);
  for (const auto& entry : std::filesystem::directory_iterator(cache))
    rests += entry.path().filename().string().rfind("slope_rest_", 0) == 0;
  EXPECT_EQ(rests, 1u);
  const Scene rougher = patched(json::parse(R"({"parameters": {"mu_rockfill": {"value": 0.3}}})"));
  run_test(rougher, rougher.resolve({}), options);
  rests = 0;
  for (const auto& entry : std::filesystem::directory_iterator(cache))
    rests += entry.path().filename().string().rfind("slope_rest_", 0) == 0;
  EXPECT_EQ(rests, 2u);
  std::filesystem::remove_all(cache);
}

TEST(Slope, ViscousBoundariesQuietItFarSoonerThanFixedOnes) {
  const TestResult viscous = run_patched(json::object());
  const TestResult fixed = run_patched(json::parse(R"({"boundaries": {
      "bottom": {"type": "velocity", "xi": null, "eta": null, "dashpot_width": null},
      "left": {"type": "fixed", "xi": null, "eta": null, "dashpot_width": null},
      "right": {"type": "fixed", "xi": null, "eta": null, "dashpot_width": null}}})"));
  ASSERT_TRUE(viscous.ok) << viscous.reason;
  ASSERT_TRUE(fixed.ok) << fixed.reason;
  // A fixed box rings until the run ends (its points never recover within 1 s); the viscous one falls quiet.
  EXPECT_GT(fixed.macro.at("total_recovery_time_s"), 2.0 * viscous.macro.at("total_recovery_time_s"));
}

TEST(Slope, BadInputFailsInOneLineNamingTheField) {
  auto expect = [](const json& patch, const std::string& message) {
    const std::string e = error_of(patch);
    EXPECT_NE(e.find(message), std::string::npos) << "expected \"" << message << "\" in: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  expect(json::parse(R"({"slope": {"bedrock": {"surface": [[0, 40], [60, 20], [50, 25], [120, 20]]}}})"),
         "slope.bedrock.surface[2]: x 50 m does not exceed the point before (60 m)");
  expect(json::parse(R"({"slope": {"bedrock": {"surface": [[0, 40], [100, 20]]}}})"),
         "slope.bedrock.surface: must run from x = 0 to x = width_m (120 m)");
  expect(json::parse(R"({"monitors": {"points": [{"label": "A", "x_m": 100, "y_m": 35}]}})"),
         "monitors.points[0]: (100, 35 m) lies outside the model");
  expect(json::parse(R"({"monitors": {"objective": ["9-9"]}})"), "monitors.objective: \"9-9\" is not a label");
  expect(json::parse(R"({"boundaries": {"top": {"type": "input", "xi": 1, "eta": 1}}})"),
         "boundaries.top: a slope's top is its free surface");
  expect(json::parse(R"({"boundaries": {"bottom": {"type": "viscous"}}})"),
         "boundaries: exactly one edge must be of type \"input\" or \"velocity\"");
  expect(json::parse(R"({"boundaries": {"left": {"dashpot_width": "half"}}})"),
         "boundaries.left.dashpot_width: \"half\" (allowed:");
  expect(json::parse(R"({"medium": {"zones": {"rockfill_upper": null}}})"),
         "medium.zones.rockfill_upper: missing; the zone's disks touch the left edge");
  expect(json::parse(R"({"slope": {"zones": [{"name": "z", "top": [[0, 30], [60, 30]], "radius_min_m": 0.5,
                                               "radius_max_m": 0.7, "density_kg_m3": 2000}]}})"),
         "slope.zones[0].top: lies nowhere a diameter above the bedrock");
}

TEST(GroundMotion, IntegratesTheRecordAndEndsItAtRest) {
  // a = A sin(2 pi t / T) over one period: v = A T / (2 pi) (1 - cos(2 pi t / T)), back to zero at T.
  const double A = 2.0, T = 1.0, dt = 0.001;
  std::vector<double> a;
  for (int k = 0; k <= 1000; ++k) a.push_back(A * std::sin(2 * M_PI * k * dt / T));
  const GroundMotion g = ground_motion(a, dt, 1.0, 0, Baseline::none);
  // The trapezoid rule's error bound: t h^2 max|a''| / 12 = 3.3e-6 m/s at t = 0.5 s.
  for (double t : {0.1, 0.25, 0.5, 0.8})
    EXPECT_NEAR(g.velocity_at(t), A * T / (2 * M_PI) * (1 - std::cos(2 * M_PI * t / T)), 3.3e-6) << t;
  EXPECT_NEAR(g.peak_speed_m_s(), A * T / M_PI, 3.3e-6);
  EXPECT_EQ(g.velocity_at(-1), 0.0);
  EXPECT_EQ(g.velocity_at(2 * T), 0.0);  // the record is over
  // A constant 1 m/s^2 drifts the velocity to 1 m/s; the baseline takes the whole of it out.
  const GroundMotion drift = ground_motion(std::vector<double>(11, 0.5), 0.1, 2.0, 0, Baseline::end_at_rest);
  EXPECT_NEAR(drift.baseline_offset_m_s2, 1.0, 1e-12);
  EXPECT_NEAR(drift.peak_speed_m_s(), 0.0, 1e-12);
  // The first half second of the record only, and the unit (g) applied.
  const GroundMotion first = ground_motion(a, dt, 9.80665, 0.5, Baseline::none);
  EXPECT_NEAR(first.duration_s(), 0.5, 1e-12);
  EXPECT_NEAR(first.peak_acceleration_m_s2(), 9.80665 * A, 1e-9);
}

TEST(GroundMotion, ReadsThePeknoldLayoutAndRefusesBadRecords) {
  double dt = 0.02;
  const std::string values = temp_file("record_values.dat", "# El Centro\n# in g\n   0.1   0.2\n\n  -0.3 0.4 0.5\n");
  EXPECT_EQ(read_acceleration_record(values, RecordFormat::values, dt, "s.json: earthquake"),
            (std::vector<double>{0.1, 0.2, -0.3, 0.4, 0.5}));
  double own = 0;
  const std::string pairs = temp_file("record_pairs.dat", "0 0.1\n0.01 0.2\n0.02 0.3\n");
  EXPECT_EQ(read_acceleration_record(pairs, RecordFormat::time_value, own, "s.json: earthquake").size(), 3u);
  EXPECT_DOUBLE_EQ(own, 0.01);
  auto error = [](const std::string& path, RecordFormat format, double step) {
    try {
      read_acceleration_record(path, format, step, "s.json: earthquake");
    } catch (const demcal::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string word = temp_file("record_word.dat", "0.1 0.2\n0.3 abc\n");
  EXPECT_NE(error(word, RecordFormat::values, 0.02).find("record_word.dat: line 2: \"abc\" is not a number"), std::string::npos);
  const std::string uneven = temp_file("record_uneven.dat", "0 0.1\n0.01 0.2\n0.02 0.3\n0.04 0.1\n");
  EXPECT_NE(error(uneven, RecordFormat::time_value, 0).find("record_uneven.dat: line 4: uneven time step (0.02 s after 0.01 s"),
            std::string::npos);
  EXPECT_NE(error(values, RecordFormat::values, 0).find("s.json: earthquake.time_step_s: missing"),
            std::string::npos);
  EXPECT_NE(error("/nonexistent/record.dat", RecordFormat::values, 0.02).find("s.json: earthquake.record_file: cannot read /nonexistent/record.dat"),
            std::string::npos);
}

TEST(Slope, AnEarthquakeRecordShakesItAndTheRunEndsWhenItIsAtRestAgain) {
  // Half a second of a 4 Hz shaking of 0.05 g, as a record file.
  std::string text = "# 4 Hz, 0.05 g\n";
  for (int k = 0; k <= 50; ++k) text += std::to_string(0.05 * std::sin(2 * M_PI * 4 * 0.01 * k)) + "\n";
  const std::string record = temp_file("shaking.dat", text);
  const json patch = {{"pulse", nullptr},
                      {"earthquake", {{"record_file", record}, {"time_step_s", 0.01}, {"units", "g"}, {"wave", "s"}}},
                      {"run", {{"duration_s", 4.0}, {"stop_force_ratio", 0.01}}}};
  const TestResult r = run_patched(patch);
  ASSERT_TRUE(r.ok) << r.reason;
  // The input's peak velocity is the record's, integrated and baseline-corrected.
  std::vector<double> a;
  for (int k = 0; k <= 50; ++k) a.push_back(std::stod(std::to_string(0.05 * std::sin(2 * M_PI * 4 * 0.01 * k))));
  const GroundMotion g = ground_motion(a, 0.01, 9.80665, 0, Baseline::end_at_rest);
  EXPECT_DOUBLE_EQ(r.macro.at("input_peak_speed_m_s"), g.peak_speed_m_s());
  // An S wave: the base point moves sideways far more than up and down.
  std::vector<double> vx, vy;
  for (const auto& [name, values] : r.series) {
    if (name == "vx_1_1_m_s") vx = values;
    if (name == "vy_1_1_m_s") vy = values;
  }
  ASSERT_FALSE(vx.empty());
  double peak_x = 0, peak_y = 0;
  for (std::size_t k = 0; k < vx.size(); ++k) {
    peak_x = std::max(peak_x, std::abs(vx[k]));
    peak_y = std::max(peak_y, std::abs(vy[k]));
  }
  EXPECT_GT(peak_x, 3 * peak_y);
  // It came to rest again before run.duration_s, after the input's 0.5 s.
  EXPECT_GT(r.macro.at("end_time_s"), 0.5);
  EXPECT_LT(r.macro.at("end_time_s"), 4.0);
  EXPECT_LT(r.macro.at("end_force_ratio"), 0.01);
  // Both inputs at once, and a record that is not one, are refused.
  EXPECT_NE(error_of({{"earthquake", {{"record_file", record}, {"time_step_s", 0.01}}}})
                .find("pulse and earthquake: give one input, not both"),
            std::string::npos);
  const std::string word = temp_file("shaking_word.dat", "0.1 0.2 x\n");
  EXPECT_NE(error_of({{"pulse", nullptr}, {"earthquake", {{"record_file", word}, {"time_step_s", 0.01}}}})
                .find("shaking_word.dat: line 1: \"x\" is not a number"),
            std::string::npos);
}

TEST(Slope, ARunThatStopsResumesFromItsCheckpointWithTheSameBits) {
  std::string text = "# 4 Hz, 0.05 g\n";
  for (int k = 0; k <= 50; ++k) text += std::to_string(0.05 * std::sin(2 * M_PI * 4 * 0.01 * k)) + "\n";
  const std::string record = temp_file("shaking_checkpoint.dat", text);
  const json quake = {{"pulse", nullptr},
                      {"earthquake", {{"record_file", record}, {"time_step_s", 0.01}}},
                      {"run", {{"duration_s", 1.5}, {"checkpoint_every_s", 0.1}}}};
  const std::string cache = ::testing::TempDir() + "slope_checkpoint_cache";
  std::filesystem::remove_all(cache);
  auto run = [&](const json& patch, const std::string& cache_dir) {
    json p = quake;
    p.merge_patch(patch);
    const Scene s = patched(p);
    RunOptions options;
    options.seed = 1;
    options.cache_dir = cache_dir;
    return run_test(s, s.resolve({}), options);
  };
  const TestResult through = run(json::object(), "");
  ASSERT_TRUE(through.ok) << through.reason;
  // The same run stopped part-way (a disk's speed limit it reaches as the shaking grows, as a crash would stop
  // it): its checkpoints stay in the cache.
  const TestResult stopped = run({{"run", {{"max_speed_m_s", 0.04}}}}, cache);
  ASSERT_FALSE(stopped.ok);
  std::size_t checkpoints = 0;
  for (const auto& entry : std::filesystem::directory_iterator(cache))
    checkpoints += entry.path().filename().string().rfind("slope_run_", 0) == 0;
  ASSERT_EQ(checkpoints, 1u) << "the stopped run left no checkpoint: " << stopped.reason;
  std::vector<double> stopped_times;
  for (const auto& [name, values] : stopped.series)
    if (name == "time_s") stopped_times = values;
  ASSERT_GT(stopped_times.back(), 0.1);  // it got past its first checkpoint
  ASSERT_LT(stopped_times.back(), 1.4);  // and stopped well before the end
  // Run again: it resumes and ends as the run that went through, to the bit; its checkpoint is then removed.
  const TestResult resumed = run(json::object(), cache);
  ASSERT_TRUE(resumed.ok) << resumed.reason;
  EXPECT_EQ(resumed.macro, through.macro);
  EXPECT_EQ(resumed.series, through.series);
  checkpoints = 0;
  for (const auto& entry : std::filesystem::directory_iterator(cache))
    checkpoints += entry.path().filename().string().rfind("slope_run_", 0) == 0;
  EXPECT_EQ(checkpoints, 0u);
  std::filesystem::remove_all(cache);
}
