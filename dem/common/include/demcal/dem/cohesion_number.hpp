#pragma once
// The cohesion number of Behjani et al. 2017 (Powder Technol. 321:461), in its
// dimensionless form: Coh = (1 / (rho g)) (w^5 / (E*^2 R*^8))^(1/3), the JKR
// pull-off force over a particle's weight up to a constant. He et al. 2019 print
// a form with R*^2 and units of m^2; this one is what stays fixed when a
// powder's contacts are softened or its particles coarse-grained: keeping Coh
// scales the work of adhesion by (E*'/E*)^(2/5) (R*'/R*)^(8/5) (rho'/rho)^(3/5).
#include <cmath>

namespace demcal::dem {

// E* of two particles of one material (Hertz): E / (2 (1 - nu^2)), E = 2 G (1 + nu).
inline double effective_modulus_pa(double shear_modulus_pa, double poisson) {
  return shear_modulus_pa * (1 + poisson) / (1 - poisson * poisson);
}

// R* of two particles of radius r: r / 2.
inline double cohesion_number(double work_of_adhesion_j_m2, double effective_modulus_pa, double effective_radius_m,
                              double density_kg_m3, double gravity_m_s2) {
  const double w = work_of_adhesion_j_m2, e = effective_modulus_pa, r = effective_radius_m;
  return std::cbrt(std::pow(w, 5) / (e * e * std::pow(r, 8))) / (density_kg_m3 * gravity_m_s2);
}

}  // namespace demcal::dem
