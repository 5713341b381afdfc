#pragma once
// Uniaxial compression between two frictionless platens: the stress-strain
// curve and the macro values a calibration targets.
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/bodies.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// Packs (or loads) the specimen, bonds it, and loads it to failure. Bad input
// throws; a run that goes unstable or times out returns ok = false with the reason.
TestResult run_ucs(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// The band of the height whose disks nu's tangent fits, as fractions of the
// height above the bottom platen: the middle three fifths. Over E's short
// window the fit to the middle third scattered 1.4-1.5x more from seed to seed
// (docs/explanation/calibration_method.md, "Which disks measure nu"); a fifth of the height is
// left out at each platen, whose frictionless contacts let the end layers
// spread more.
inline constexpr double kNuGaugeBottomFraction = 0.2;
inline constexpr double kNuGaugeTopFraction = 0.8;

// The disks whose centres lie between bottom_m and top_m (inclusive), measured
// from y0_m: a gauge band of the specimen, as indices into `b` in the order of
// the disks' ids (so a gauge's sums do not depend on how the disks are stored).
std::vector<std::size_t> disks_in_band(const Bodies& b, double y0_m, double bottom_m, double top_m);

// The lateral strain of a set of disks as the least-squares slope of their
// x-displacement on their initial x: the strain a measurement region fits
// (as PFC's measure logic fits a strain rate to the balls in a circle). Every
// disk of the set counts, so it scatters less than the widening between two
// edge gauges, and a short tangent window amplifies that scatter.
class LateralStrainFit {
 public:
  // ids: the disks to fit (at least two distinct x); x: their positions now.
  LateralStrainFit(const std::vector<double>& x, std::vector<std::size_t> ids);
  double strain(const std::vector<double>& x) const;

 private:
  std::vector<std::size_t> ids_;
  std::vector<double> x0_, centred_x0_;
  double sxx_ = 0;
};

}  // namespace demcal::dem
