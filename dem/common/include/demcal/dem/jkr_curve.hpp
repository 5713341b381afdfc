#pragma once
// The JKR curve of two elastic spheres (Johnson, Kendall & Roberts 1971), the
// same in 2D (a disk taken as the sphere of its radius) and in 3D, for a work
// of adhesion w (J/m^2, the energy per area to separate two surfaces), the
// effective modulus E* and radius R*:
//   F = 4 E* a^3 / (3 R*) - sqrt(8 pi w E* a^3),   delta = a^2 / R* - sqrt(2 pi w a / E*)
// Its least force is the pull-off -1.5 pi w R*; the curve ends at the
// separation delta_c = -delta(a_c), a_c = (pi w R*^2 / (8 E*))^(1/3). With
// w = 0 it is Hertz's.
#include <algorithm>
#include <cmath>

namespace demcal::dem {

struct JkrCurve {
  double e_eff_pa = 0;
  double work_of_adhesion_j_m2 = 0;
  double adhesion = 0;  // sqrt(2 pi w / E*), m^(1/2)

  JkrCurve() = default;
  JkrCurve(double e_eff, double work_of_adhesion)
      : e_eff_pa(e_eff), work_of_adhesion_j_m2(work_of_adhesion),
        adhesion(std::sqrt(2.0 * M_PI * work_of_adhesion / e_eff)) {}

  // delta_c = -delta(a_c) for the effective radius R*.
  double separation_limit(double radius) const {
    const double ac = std::cbrt(M_PI * work_of_adhesion_j_m2 * radius * radius / (8.0 * e_eff_pa));
    return std::max(0.0, -(ac * ac / radius - adhesion * std::sqrt(ac)));
  }

  // a on the stable branch (a >= a_c) for overlap delta: the root of
  // s^4 / R - c s - delta in s = sqrt(a). The function is convex and rising
  // there, so Newton from a point right of the root falls to it monotonically;
  // the pair's last a is such a point when it is not left of the root.
  double contact_radius(double delta, double radius, double last_a) const {
    if (adhesion == 0.0) return std::sqrt(radius * std::max(0.0, delta));
    auto excess = [&](double s) { return s * s * s * s / radius - adhesion * s - delta; };
    // s >= s_c = cbrt(adhesion R / 4) is where the curve rises: 4 s^3 / R >= adhesion. Tested that way, the
    // cube root (a tenth of a heap's time) is taken only on the rare paths that need its value.
    auto rising = [&](double s) { return 4.0 * s * s * s / radius - adhesion; };
    double s = std::sqrt(last_a);
    if (!(rising(s) >= 0 && excess(s) >= 0))
      s = std::max(std::sqrt(std::sqrt(2.0 * radius * std::max(0.0, delta))), std::cbrt(2.0 * adhesion * radius));
    for (int iteration = 0; iteration < 100; ++iteration) {
      const double slope = rising(s);
      if (!(slope > 0)) break;  // at a_c itself: the root is s_critical
      const double step = excess(s) / slope;
      s -= step;
      if (!(step > 1e-15 * s)) break;
    }
    if (!(rising(s) > 0)) s = std::max(s, std::cbrt(0.25 * adhesion * radius));
    return s * s;
  }

  // The repulsive (Hertz) part of the force at contact radius a, as the
  // Hertz-Mindlin models write it (w = 0 gives their bits).
  double repulsive_n(double a, double radius) const { return 4.0 / 3.0 * e_eff_pa * a * a * a / radius; }
  // The whole force: the repulsive part less the adhesion.
  double total_n(double repulsive, double a) const {
    return repulsive - std::sqrt(8.0 * M_PI * work_of_adhesion_j_m2 * e_eff_pa * a * a * a);
  }
};

}  // namespace demcal::dem
