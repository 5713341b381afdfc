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

}  // namespace

std::pair<double, double> Element::extent(double a1, double a2) const {
  // A linear function's extremes over the sector lie on its edges: at the
  // four corners, or where an arc faces along (a1, a2) or against it (r a /
  // |a| from the disc's centre, when that direction lies in the sector).
  double lo = INFINITY, hi = -INFINITY;
  for (int c = 0; c < 4; ++c) {
    const double value = a1 * corner1[c] + a2 * corner2[c];
    lo = std::min(lo, value), hi = std::max(hi, value);
  }
  const double size = std::hypot(a1, a2);
  if (size == 0) return {lo, hi};
  const double centroid = a1 * x1 + a2 * x2;
  const double span = angle_to - angle_from;
  // Whether the unit direction (d1, d2) lies between the straight edges.
  const auto inside = [&](double d1, double d2) {
    if (span >= 2 * M_PI - 1e-12) return true;
    return from1 * d2 - from2 * d1 >= 0 && d1 * to2 - d2 * to1 >= 0;
  };
  for (const double sign : {1.0, -1.0})
    if (inside(sign * a1 / size, sign * a2 / size))
      for (const double r : {r_inner, r_outer}) {
        const double value = sign * r * size - centroid;
        lo = std::min(lo, value), hi = std::max(hi, value);
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
      int corner = 0;
      for (double r : {e.r_inner, e.r_outer})
        for (double angle : {e.angle_from, e.angle_to}) {
          e.corner1[corner] = r * std::cos(angle) - e.x1, e.corner2[corner] = r * std::sin(angle) - e.x2;
          ++corner;
        }
      e.from1 = std::cos(e.angle_from), e.from2 = std::sin(e.angle_from);
      e.to1 = std::cos(e.angle_to), e.to2 = std::sin(e.angle_to);
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
