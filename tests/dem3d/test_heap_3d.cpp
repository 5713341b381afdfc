// The 3D funnel heap's parts against closed forms: the mass and inertia of a
// two-sphere clump, the random fill of a funnel, the angle fitted over
// vertical sections of a cone of known slope; and its scene's bad input. The
// whole test runs in the invariant driver (tests/invariants/lab_tests/heap_3d.json).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/scene_error.hpp"
#include "../common/scratch.hpp"
#include "demcal/core/error.hpp"
#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem3d/clump.hpp"
#include "demcal/dem3d/heap_section_fit.hpp"
#include "demcal/dem3d/powder_3d.hpp"

using namespace demcal;
using namespace demcal::dem3d;

namespace {

constexpr double kRho = 1500.0;

// The union's slices along its axis, integrated by Simpson's rule: an
// independent check of the closed forms.
TwoSphereUnion union_by_slices(double r, double d) {
  const double s = 0.5 * d, top = s + r;
  const int n = 20000;  // even
  const double h = 2 * top / n;
  double mass = 0, axial = 0, transverse = 0;
  for (int k = 0; k <= n; ++k) {
    const double z = -top + k * h;
    const double a2 = std::max({0.0, r * r - (z - s) * (z - s), r * r - (z + s) * (z + s)});
    const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    mass += w * kRho * M_PI * a2;
    axial += w * kRho * M_PI * a2 * a2 / 2;
    transverse += w * kRho * M_PI * (a2 * a2 / 4 + z * z * a2);
  }
  return {mass * h / 3, axial * h / 3, transverse * h / 3};
}

TEST(TwoSphereUnion, ASphereTwoTouchingSpheresAndTheLensBetween) {
  const double r = 0.002, m1 = 4.0 / 3.0 * M_PI * r * r * r * kRho;
  const TwoSphereUnion one = two_sphere_union(r, 0.0, kRho);
  EXPECT_NEAR(one.mass_kg / m1, 1.0, 1e-14);
  EXPECT_NEAR(one.axial_inertia_kg_m2 / (0.4 * m1 * r * r), 1.0, 1e-14);
  EXPECT_NEAR(one.transverse_inertia_kg_m2 / (0.4 * m1 * r * r), 1.0, 1e-14);
  // Touching: nothing shared, so the clump of two spheres is exact.
  const TwoSphereUnion two = two_sphere_union(r, 2 * r, kRho);
  const ClumpShape pair = clump_of_spheres({{0, 0, -r}, {0, 0, r}}, {r, r}, kRho);
  EXPECT_NEAR(two.mass_kg / pair.mass_kg, 1.0, 1e-12);
  const double i_max = std::max({pair.principal_inertia_kg_m2.x, pair.principal_inertia_kg_m2.y,
                                 pair.principal_inertia_kg_m2.z});
  const double i_min = std::min({pair.principal_inertia_kg_m2.x, pair.principal_inertia_kg_m2.y,
                                 pair.principal_inertia_kg_m2.z});
  EXPECT_NEAR(two.transverse_inertia_kg_m2 / i_max, 1.0, 1e-12);
  EXPECT_NEAR(two.axial_inertia_kg_m2 / i_min, 1.0, 1e-12);
  // He et al.'s aspect ratio 1.3: d = 0.6 r; the lens is two caps of height r - d/2, pi h^2 (3r - h) / 3 each.
  const double d = 0.6 * r, cap_h = r - 0.5 * d;
  const double lens = 2 * M_PI * cap_h * cap_h * (3 * r - cap_h) / 3;
  const TwoSphereUnion clump = two_sphere_union(r, d, kRho);
  EXPECT_NEAR(clump.mass_kg / (2 * m1 - kRho * lens), 1.0, 1e-13);
  const TwoSphereUnion sliced = union_by_slices(r, d);
  EXPECT_NEAR(clump.mass_kg / sliced.mass_kg, 1.0, 1e-9);
  EXPECT_NEAR(clump.axial_inertia_kg_m2 / sliced.axial_inertia_kg_m2, 1.0, 1e-9);
  EXPECT_NEAR(clump.transverse_inertia_kg_m2 / sliced.transverse_inertia_kg_m2, 1.0, 1e-9);
  EXPECT_THROW(two_sphere_union(r, 2.1 * r, kRho), Error);
}

PowderSpec3d powder() {
  PowderSpec3d p;
  p.radius_min_m = 0.001;
  p.radius_max_m = 0.0012;
  p.density_kg_m3 = kRho;
  p.clump_aspect_ratio = 1.3;
  p.solids_fraction = 0.25;
  return p;
}

TEST(PowderFill3d, EverySphereInsideNoneOverlappingTheFractionReachedAndSeeded) {
  const Frustum funnel{0.03, 0.05, 0.008, 0.02};
  const PowderSpec3d spec = powder();
  const std::vector<PowderParticle3d> a = place_powder_3d(spec, funnel, 3, "test");
  std::vector<Vec3> centres;
  std::vector<double> radii;
  double volume = 0;
  for (const PowderParticle3d& p : a) {
    ASSERT_TRUE(p.clump);
    for (const Vec3& c : member_centres(p, spec.clump_aspect_ratio)) {
      EXPECT_TRUE(funnel.holds(c, p.radius_m));
      centres.push_back(c);
      radii.push_back(p.radius_m);
    }
    EXPECT_NEAR(norm(member_centres(p, 1.3)[1] - member_centres(p, 1.3)[0]), 0.6 * p.radius_m, 1e-15);
    volume += two_sphere_union(p.radius_m, 0.6 * p.radius_m, 1.0).mass_kg;
  }
  for (std::size_t i = 0; i < centres.size(); ++i) {
    for (std::size_t j = i + 1; j < centres.size(); ++j) {
      if (i / 2 == j / 2) continue;  // a clump's own two spheres (2k, 2k + 1) overlap by design
      ASSERT_GE(norm(centres[i] - centres[j]), radii[i] + radii[j] - 1e-15) << i << " " << j;
    }
  }
  EXPECT_GE(volume, spec.solids_fraction * funnel.volume_m3());
  EXPECT_LT(volume, spec.solids_fraction * funnel.volume_m3() + 2 * two_sphere_union(0.0012, 0.00072, 1.0).mass_kg);
  const std::vector<PowderParticle3d> again = place_powder_3d(spec, funnel, 3, "test");
  const std::vector<PowderParticle3d> other = place_powder_3d(spec, funnel, 4, "test");
  ASSERT_EQ(again.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(again[k].centre_m.x, a[k].centre_m.x);
  EXPECT_NE(other.front().centre_m.x, a.front().centre_m.x);
}

// The sizes are uniform over [min, max] however crowded the fill: they are
// drawn first and placed the largest first (drawing a size per try favoured
// the small ones, which fit more easily). The mean within 3 standard errors of
// a uniform's.
TEST(PowderFill3d, TheSizesStayUniformInACrowdedFill) {
  PowderSpec3d spec = powder();
  spec.radius_min_m = 0.001;
  spec.radius_max_m = 0.002;
  spec.clump_aspect_ratio = 1.0;
  spec.solids_fraction = 0.3;
  const std::vector<PowderParticle3d> fill = place_powder_3d(spec, Frustum{0.0, 0.06, 0.035, 0.035}, 5, "test");
  ASSERT_GT(fill.size(), 3000u);
  double sum = 0;
  for (const PowderParticle3d& p : fill) sum += p.radius_m;
  const double n = static_cast<double>(fill.size()), standard_error = 0.001 / std::sqrt(12.0 * n);
  EXPECT_NEAR(sum / n, 0.0015, 3 * standard_error);
}

TEST(PowderFill3d, AFillThatDoesNotFitItsVesselIsAnError) {
  PowderSpec3d spec = powder();
  spec.solids_fraction = 0.35;
  spec.max_attempts_per_particle = 500;
  try {
    place_powder_3d(spec, Frustum{0.0, 0.008, 0.004, 0.006}, 1, "scene.json: funnel (the fill)");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json: funnel (the fill): placed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not fit its vessel"), std::string::npos) << e.what();
  }
}

// Spheres whose tops lie on a cone of slope tan(angle) around the z axis,
// on a square grid over a disk of radius `radius`.
void cone_of_spheres(double angle_deg, double radius, double r, std::vector<double>& x, std::vector<double>& y,
                     std::vector<double>& z, std::vector<double>& rr) {
  const double slope = std::tan(angle_deg * M_PI / 180), apex = slope * radius;
  for (double px = -radius; px <= radius; px += r)
    for (double py = -radius; py <= radius; py += r) {
      const double rho = std::hypot(px, py);
      if (rho > radius) continue;
      x.push_back(px);
      y.push_back(py);
      z.push_back(apex - slope * rho - r);
      rr.push_back(r);
    }
}

TEST(HeapSections, AConeOfKnownSlopeGivesItsAngleInEverySection) {
  for (double angle : {25.0, 35.0, 47.8}) {
    std::vector<double> x, y, z, r;
    cone_of_spheres(angle, 0.03, 0.001, x, y, z, r);
    HeapSectionOptions options;
    options.sections = 6;
    options.slab_width_m = 0.004;
    options.profile.bin_width_m = 0.002;
    const HeapSectionFit fit = fit_heap_sections(x, y, z, r, 0.0, options);
    ASSERT_EQ(fit.flank_deg.size(), 12u);
    // The tops are sampled on a grid, so a bin's highest top lies up to a bin width uphill of its centre: the
    // lines' slopes stay those of the cone to within the sampling.
    EXPECT_NEAR(fit.mean_deg, angle, 0.5) << angle;
    for (double a : fit.flank_deg) EXPECT_NEAR(a, angle, 1.5) << angle;
    EXPECT_LT(fit.sd_deg, 1.0);
    EXPECT_NEAR(fit.height_m, 0.03 * std::tan(angle * M_PI / 180), 0.002 * std::tan(angle * M_PI / 180) + 1e-9);
  }
}

// The small heap of the invariant driver, edited.
nlohmann::json small_heap() {
  std::ifstream in(std::string(DEMCAL_SOURCE_DIR) + "/tests/invariants/scenes/heap_small_3d.json");
  return nlohmann::json::parse(in);
}

std::string scene_error(const nlohmann::json& scene) { return test::scene_error(scene, "heap_3d_bad.json"); }

TEST(HeapTest3d, BadScenesNameTheFileAndField) {
  nlohmann::json s = small_heap();
  s["funnel"]["outlet_diameter_m"] = 0.008;
  EXPECT_NE(scene_error(s).find("heap_3d_bad.json: funnel.outlet_diameter_m 0.008 m is less than 4 particle lengths"),
            std::string::npos) << scene_error(s);
  s = small_heap();
  s["funnel"]["domain_diameter_m"] = 0.026;
  EXPECT_NE(scene_error(s).find("funnel.domain_diameter_m 0.026 m must exceed platform_diameter_m"), std::string::npos)
      << scene_error(s);
  s = small_heap();
  s["parameters"]["w_N_m"]["value"] = -0.1;
  s["parameters"]["w_N_m"]["low"] = -1;
  EXPECT_NE(scene_error(s).find("work_of_adhesion_j_m2"), std::string::npos) << scene_error(s);
  s = small_heap();
  s["contacts"]["particle-particle"]["parameters"]["restitution"] = 1.2;
  EXPECT_NE(scene_error(s).find("restitution"), std::string::npos) << scene_error(s);
  s = small_heap();
  s["run"]["sections"] = 2.5;
  EXPECT_NE(scene_error(s).find("run.sections must be a whole number"), std::string::npos) << scene_error(s);
  s = small_heap();
  s["particles"]["radius_min_m"] = 0.002;
  EXPECT_NE(scene_error(s).find("particles: radius_min_m and radius_max_m"), std::string::npos) << scene_error(s);
}

}  // namespace

namespace {

TEST(HeapTest3d, ARayleighFractionFixesTheStep) {
  // A fixed step of 0.08 of the smallest sphere's Rayleigh step pi R sqrt(rho / G) / (0.1631 nu + 0.8766); the
  // run is cut short (not discharged), but reports the step it took.
  nlohmann::json s = small_heap();
  s["run"]["rayleigh_fraction"] = 0.08;
  s["run"]["max_time_s"] = 0.02;
  const std::string path = test::scratch_path("heap_3d_rayleigh.json");
  std::ofstream(path) << s.dump();
  const dem::Scene scene = dem::Scene::load(path);
  dem::RunOptions options;
  const dem::TestResult r = dem::run_test(scene, scene.resolve({}), options);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("had not discharged within run.max_time_s"), std::string::npos) << r.reason;
  const double rayleigh = M_PI * 0.001 * std::sqrt(1000 / 1e4) / (0.1631 * 0.3 + 0.8766);
  EXPECT_NEAR(r.dt_s, 0.08 * rayleigh, 1e-15);
  EXPECT_NEAR(r.specimen_info.at("dt_over_rayleigh_step"), 0.08, 1e-12);
  s["run"]["rayleigh_fraction"] = 0.6;
  EXPECT_NE(scene_error(s).find("run.rayleigh_fraction must lie in [0, 0.5]"), std::string::npos) << scene_error(s);
}

}  // namespace

namespace {

dem::TestResult run_small(const nlohmann::json& s, const std::string& name) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path) << s.dump();
  const dem::Scene scene = dem::Scene::load(path);
  return dem::run_test(scene, scene.resolve({}), dem::RunOptions{});
}

// The brush: its blades' places are left out of the fill (the same fill as
// without a brush, less those), it turns at its rpm from the gate's opening
// until the funnel has discharged and then stands still while the heap
// settles (it settled 0.3 s after the discharge here; a brush still turning
// would have made twice the turns).
TEST(HeapTest3d, TheBrushTurnsWhileTheFunnelDischargesOnly) {
  nlohmann::json s = small_heap();
  s["run"]["discharged_fraction"] = 0.6;
  s["run"]["settle_kinetic_ratio"] = 1e-2;
  nlohmann::json unbrushed = s;
  unbrushed["run"]["max_time_s"] = 0.02;  // the fill is all this needs
  const dem::TestResult without = run_small(unbrushed, "heap_3d_no_brush.json");
  s["brush"] = {{"rpm", 120}};
  const dem::TestResult with = run_small(s, "heap_3d_brush.json");
  ASSERT_TRUE(with.ok) << with.reason;
  const double left_out = with.specimen_info.at("left_out_for_brush");
  EXPECT_GT(left_out, 0.0);
  EXPECT_EQ(with.specimen_info.at("particles") + left_out, without.specimen_info.at("particles"));
  const double check_s = s["run"]["check_every_s"].get<double>();
  const double turns = with.specimen_info.at("brush_turns"), flow_s = with.macro.at("flow_time_s");
  EXPECT_NEAR(turns, 2.0 * flow_s, 2.0 * check_s);
  EXPECT_GT(with.specimen_info.at("settled_at_s") - 0.01 - flow_s, 0.1);  // it stood still that long
}

TEST(HeapTest3d, BadBrushesNameTheField) {
  nlohmann::json s = small_heap();
  s["brush"] = {{"rpm", 0}};
  EXPECT_NE(scene_error(s).find("heap_3d_bad.json: brush.rpm must be positive"), std::string::npos) << scene_error(s);
  s["brush"] = {{"rpm", 60}, {"blades", 2.5}};
  EXPECT_NE(scene_error(s).find("brush.blades must be a whole number"), std::string::npos) << scene_error(s);
  s["brush"] = {{"rpm", 60}, {"clearance_m", 0.01}};
  EXPECT_NE(scene_error(s).find("brush.clearance_m must lie in"), std::string::npos) << scene_error(s);
  s["brush"] = {{"rpm", 60}, {"speed", 1}};
  EXPECT_NE(scene_error(s).find("speed"), std::string::npos) << scene_error(s);
}

}  // namespace
