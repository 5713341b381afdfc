#pragma once
// Uniaxial compression between two frictionless platens: the stress-strain
// curve and the macro values a calibration targets.
#include <map>
#include <string>
#include <vector>

#include "demcal/dem/scene.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// Packs (or loads) the specimen, bonds it, and loads it to failure. Bad input
// throws; a run that goes unstable or times out returns ok = false with the reason.
TestResult run_ucs(const Scene& scene, const std::map<std::string, double>& parameters, const RunOptions& options);

// sigma_u, E (tangent where the stress first reaches half the peak, a
// least-squares slope over its neighbours), E50 (secant there), nu (tangent
// d eps_lat / d eps_ax over E's window), nu50 (secant eps_lat / eps_ax at the
// half-peak point) and the peak strain. nu50 uses the curve's lateral strain;
// nu uses `tangent_lateral_strain` (one value per curve point) when given,
// else the curve's too.
std::map<std::string, double> ucs_macro_values(const std::vector<CurvePoint>& curve,
                                               const std::vector<double>* tangent_lateral_strain = nullptr);

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
