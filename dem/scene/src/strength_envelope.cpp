#include "demcal/dem/strength_envelope.hpp"

#include <cmath>
#include <string>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/line_fit.hpp"

namespace demcal::dem {
namespace {

// The fits' own messages for too few peaks and for confining stresses all alike.
FittedLine fit_peaks(const std::vector<double>& x, const std::vector<double>& y, const char* what) {
  return fit_line(x, y, std::string("the ") + what + " fit needs at least two peaks",
                  std::string("the ") + what + " fit needs at least two different confining stresses");
}

}  // namespace

MohrCoulombFit fit_mohr_coulomb(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa) {
  const FittedLine line = fit_peaks(sigma_3_pa, sigma_1_pa, "Mohr-Coulomb");
  MohrCoulombFit fit;
  fit.n_phi = line.slope;
  fit.sigma_c_pa = line.intercept;
  if (!(fit.n_phi > 0))
    throw Error("the Mohr-Coulomb fit gives a slope N_phi = " + format_double(fit.n_phi) +
                " <= 0 (the peak strength falls as the confinement rises): no friction angle");
  fit.phi_deg = std::asin((fit.n_phi - 1) / (fit.n_phi + 1)) * 180 / M_PI;
  fit.c_pa = fit.sigma_c_pa / (2 * std::sqrt(fit.n_phi));
  fit.r2 = line.r2;
  return fit;
}

HoekBrownFit fit_hoek_brown(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa) {
  if (sigma_1_pa.size() != sigma_3_pa.size()) throw Error("the Hoek-Brown fit needs one sigma_1 per sigma_3");
  std::vector<double> y(sigma_3_pa.size());
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = (sigma_1_pa[k] - sigma_3_pa[k]) * (sigma_1_pa[k] - sigma_3_pa[k]);
  const FittedLine line = fit_peaks(sigma_3_pa, y, "Hoek-Brown");
  if (!(line.intercept > 0))
    throw Error("the Hoek-Brown fit gives (sigma_1 - sigma_3)^2 = " + format_double(line.intercept * 1e-12) +
                " MPa^2 <= 0 at sigma_3 = 0: no uniaxial strength sigma_c");
  HoekBrownFit fit;
  fit.sigma_c_pa = std::sqrt(line.intercept);
  fit.m_i = line.slope / fit.sigma_c_pa;
  if (!(fit.m_i > 0))
    throw Error("the Hoek-Brown fit gives m_i = " + format_double(fit.m_i) +
                " <= 0 (the peak strength does not grow with the confinement)");
  fit.r2 = line.r2;
  return fit;
}

}  // namespace demcal::dem
