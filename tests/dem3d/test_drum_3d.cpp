// The rotating drum's parts: the free surface's fit against a bed of known
// slope, and its scene's bad input (a speed that centrifuges the powder among
// them). The whole test runs in the invariant driver
// (tests/invariants/lab_tests/drum_3d.json).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/scene_error.hpp"
#include "../common/scratch.hpp"
#include "demcal/core/error.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/drum_surface.hpp"

using namespace demcal;
using namespace demcal::dem3d;

namespace {

// Spheres on a square grid filling the part of a circle of radius R below the
// line z = z0 + tan(angle) x, tops on it (the bins' highest tops).
void tilted_bed(double angle_deg, double big_r, double r, std::vector<double>& x, std::vector<double>& z,
                std::vector<double>& rr) {
  const double slope = std::tan(angle_deg * M_PI / 180), z0 = -0.2 * big_r;
  for (double px = -big_r; px <= big_r; px += r) {
    const double surface = z0 + slope * px;
    for (double pz = surface - r; pz >= -big_r; pz -= 2 * r) {
      if (std::hypot(px, pz) > big_r - r) continue;
      x.push_back(px);
      z.push_back(pz);
      rr.push_back(r);
    }
  }
}

TEST(DrumSurface, ABedOfKnownSlopeGivesItsAngle) {
  for (double angle : {20.0, 35.0, 47.8}) {
    std::vector<double> x, z, r;
    tilted_bed(angle, 0.0225, 0.0005, x, z, r);
    EXPECT_NEAR(drum_surface_angle_deg(x, z, r, 0.0225, 0.001, 0.6), angle, 0.5) << angle;
  }
  EXPECT_THROW(drum_surface_angle_deg({}, {}, {}, 0.0225, 0.001, 0.6), Error);
}

nlohmann::json small_drum() {
  std::ifstream in(std::string(DEMCAL_SOURCE_DIR) + "/tests/invariants/scenes/drum_small_3d.json");
  return nlohmann::json::parse(in);
}

std::string scene_error(const nlohmann::json& scene) { return test::scene_error(scene, "drum_3d_bad.json"); }

TEST(DrumTest3d, BadScenesNameTheFileAndField) {
  nlohmann::json s = small_drum();
  s["drum"]["speed_rpm"] = 300;
  EXPECT_NE(scene_error(s).find("drum_3d_bad.json: drum.speed_rpm 300 centrifuges the powder: the Froude number"),
            std::string::npos) << scene_error(s);
  s = small_drum();
  s["drum"]["inner_diameter_m"] = 0.02;
  EXPECT_NE(scene_error(s).find("drum.inner_diameter_m 0.02 m is less than 8 particle lengths"), std::string::npos)
      << scene_error(s);
  s = small_drum();
  s["drum"]["fill_fraction"] = 0.7;
  EXPECT_NE(scene_error(s).find("drum.fill_fraction must lie in (0, 0.6]"), std::string::npos) << scene_error(s);
  s = small_drum();
  s["run"]["sample_every_s"] = 0.2;
  EXPECT_NE(scene_error(s).find("run.sample_every_s must lie in (0, measure_time_s / 4]"), std::string::npos)
      << scene_error(s);
  s = small_drum();
  s["run"]["rayleigh_fraction"] = -0.1;
  EXPECT_NE(scene_error(s).find("run.rayleigh_fraction must lie in [0, 0.5]"), std::string::npos) << scene_error(s);
}

}  // namespace

namespace {

TEST(DrumTest3d, ARunThatIsNotSteadySaysSoAndKeepsItsSamples) {
  // The small drum's angle wanders by degrees between the halves of its window: a tolerance of a thousandth of a
  // degree fails it, with the halves' means, and the samples stay in the curve for the user to see why.
  nlohmann::json s = small_drum();
  s["run"]["steady_tolerance_deg"] = 0.001;
  const std::string path = test::scratch_path("drum_3d_unsteady.json");
  std::ofstream(path) << s.dump();
  const dem::Scene scene = dem::Scene::load(path);
  const dem::TestResult r = dem::run_test(scene, scene.resolve({}), dem::RunOptions{});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("no steady state: the surface's angle moved from"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("The samples scatter by"), std::string::npos) << r.reason;  // how steady is steady
  ASSERT_EQ(r.curve.size(), 9u);  // 0.4 s sampled every 0.05 s, both ends
  EXPECT_NEAR(r.curve.front().axial_strain, 0.2 + 0.4, 1e-12);
  EXPECT_GT(r.specimen_info.at("samples"), 8.0);
  EXPECT_TRUE(r.macro.empty());
}

}  // namespace
