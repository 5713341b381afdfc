#pragma once
// Strength envelopes fitted to the peaks of a biaxial series: the straight
// Mohr-Coulomb line and the curved Hoek-Brown criterion of intact rock. Both
// are least-squares fits on (sigma_3, sigma_1) pairs in Pa, compression
// positive.
#include <vector>

namespace demcal::dem {

// sigma_1 = sigma_c + N_phi sigma_3: N_phi = (1 + sin phi) / (1 - sin phi),
// c = sigma_c / (2 sqrt(N_phi)).
struct MohrCoulombFit {
  double sigma_c_pa = 0;  // intercept: the envelope's uniaxial strength
  double n_phi = 0;       // slope
  double phi_deg = 0;
  double c_pa = 0;
  double r2 = 0;          // of the line (1 for two points)
};
// Needs at least two different sigma_3 and a positive slope (else an Error saying so).
MohrCoulombFit fit_mohr_coulomb(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa);

// Hoek-Brown for intact rock, sigma_1 = sigma_3 + sigma_c sqrt(m_i sigma_3 /
// sigma_c + 1), fitted as Hoek & Brown (1997) do: the straight line
// y = (sigma_1 - sigma_3)^2 = m_i sigma_c sigma_3 + sigma_c^2, so sigma_c^2 is
// the intercept and m_i the slope over sigma_c; r2 is that line's.
struct HoekBrownFit {
  double sigma_c_pa = 0;
  double m_i = 0;
  double r2 = 0;
};
// Needs at least two different sigma_3, a positive intercept (else there is
// no sigma_c) and a positive slope (else an Error saying which).
HoekBrownFit fit_hoek_brown(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa);

}  // namespace demcal::dem
