#include "demcal/dem/strength_envelope.hpp"

#include <cmath>
#include <string>

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem {
namespace {

// The least-squares line y = a + b x with its R^2.
struct Line {
  double intercept = 0, slope = 0, r2 = 0;
};

Line fit_line(const std::vector<double>& x, const std::vector<double>& y, const char* what) {
  if (x.size() != y.size() || x.size() < 2) throw Error(std::string("the ") + what + " fit needs at least two peaks");
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
  }
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double dx = x[k] - mx, dy = y[k] - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  if (!(sxx > 0)) throw Error(std::string("the ") + what + " fit needs at least two different confining stresses");
  Line line;
  line.slope = sxy / sxx;
  line.intercept = my - line.slope * mx;
  line.r2 = syy > 0 ? sxy * sxy / (sxx * syy) : 1.0;
  return line;
}

}  // namespace

MohrCoulombFit fit_mohr_coulomb(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa) {
  const Line line = fit_line(sigma_3_pa, sigma_1_pa, "Mohr-Coulomb");
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
  const Line line = fit_line(sigma_3_pa, y, "Hoek-Brown");
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
