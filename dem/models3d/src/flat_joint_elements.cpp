#include "flat_joint_elements.hpp"

#include <algorithm>
#include <cmath>

namespace demcal::dem3d::flat_joint {
namespace {

// The area, first and second moments of an annular sector about the disc's
// centre (closed forms: integrals of r^n dr times those of cos, sin over the angle).
struct Moments {
  double area, m1, m2, m11, m22, m12;
};
Moments sector_moments(double r0, double r1, double a0, double a1) {
  const double d2 = (r1 * r1 - r0 * r0) / 2, d3 = (r1 * r1 * r1 - r0 * r0 * r0) / 3;
  const double d4 = (std::pow(r1, 4) - std::pow(r0, 4)) / 4, span = a1 - a0;
  const double sin2 = (std::sin(2 * a1) - std::sin(2 * a0)) / 4;
  return {span * d2,
          d3 * (std::sin(a1) - std::sin(a0)),
          d3 * (std::cos(a0) - std::cos(a1)),
          d4 * (span / 2 + sin2),
          d4 * (span / 2 - sin2),
          d4 * (std::sin(a1) * std::sin(a1) - std::sin(a0) * std::sin(a0)) / 2};
}

// Whether angle `a` lies in [from, to] up to whole turns.
bool within(double a, double from, double to) {
  const double turn = 2 * M_PI;
  double x = std::fmod(a - from, turn);
  if (x < 0) x += turn;
  return x <= to - from;
}

}  // namespace

std::pair<double, double> Element::extent(double a1, double a2) const {
  // A linear function's extremes over the sector lie on its edges: at the
  // four corners, or where an arc faces along (a1, a2) or against it.
  double lo = INFINITY, hi = -INFINITY;
  const auto at = [&](double r, double angle) {
    const double value = a1 * (r * std::cos(angle) - x1) + a2 * (r * std::sin(angle) - x2);
    lo = std::min(lo, value), hi = std::max(hi, value);
  };
  for (double r : {r_inner, r_outer})
    for (double angle : {angle_from, angle_to}) at(r, angle);
  if (a1 != 0 || a2 != 0) {
    const double facing = std::atan2(a2, a1);
    for (double r : {r_inner, r_outer})
      for (double angle : {facing, facing + M_PI})
        if (within(angle, angle_from, angle_to)) at(r, angle);
  }
  return {lo, hi};
}

std::vector<Element> unit_disc_elements(int radial, int circumferential) {
  std::vector<Element> elements;
  const double span = 2 * M_PI / circumferential;
  const int cells_deep = static_cast<int>(std::ceil(4.0 / radial));
  const int cells_wide = static_cast<int>(std::ceil(18.0 / circumferential - 1e-9));
  for (int a = 0; a < radial; ++a)
    for (int b = 0; b < circumferential; ++b) {
      Element e;
      e.r_inner = static_cast<double>(a) / radial, e.r_outer = static_cast<double>(a + 1) / radial;
      e.angle_from = b * span, e.angle_to = (b + 1) * span;
      const Moments m = sector_moments(e.r_inner, e.r_outer, e.angle_from, e.angle_to);
      e.area = m.area;
      e.x1 = m.m1 / m.area, e.x2 = m.m2 / m.area;
      // About the centroid (parallel axes).
      e.s11 = m.m11 - m.area * e.x1 * e.x1;
      e.s22 = m.m22 - m.area * e.x2 * e.x2;
      e.s12 = m.m12 - m.area * e.x1 * e.x2;
      // Sub-cells: the same split of this sector, each with its own moments.
      const double dr = (e.r_outer - e.r_inner) / cells_deep, da = span / cells_wide;
      for (int p = 0; p < cells_deep; ++p)
        for (int q = 0; q < cells_wide; ++q) {
          const double a0 = e.angle_from + q * da, a1 = a0 + da, middle = a0 + da / 2;
          const Moments c = sector_moments(e.r_inner + p * dr, e.r_inner + (p + 1) * dr, a0, a1);
          const double c1 = c.m1 / c.area, c2 = c.m2 / c.area;
          e.cells.push_back({c.area, c1 - e.x1, c2 - e.x2, c.m11 - c.area * c1 * c1, c.m22 - c.area * c2 * c2,
                             c.m12 - c.area * c1 * c2, std::cos(middle), std::sin(middle), dr,
                             std::hypot(c1, c2) * da});
        }
      elements.push_back(std::move(e));
    }
  return elements;
}

}  // namespace demcal::dem3d::flat_joint
