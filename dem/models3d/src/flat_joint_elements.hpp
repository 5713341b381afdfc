#pragma once
// The 3D flat joint's interface: a disc of radius R split into rings of
// equal width (radial elements) and equal sectors (circumferential
// elements), as PFC3D's flat joint splits it (fj_nr x fj_na). Each element
// is an annular sector; this file holds its shape in units of R, in the
// joint's own plane frame (t1, t2): area, centroid, second moments about the
// centroid, and a grid of sub-cells (at most R/4 deep and 20 degrees wide)
// for a broken element that is pressed over part of its face only.
#include <utility>
#include <vector>

namespace demcal::dem3d::flat_joint {

struct SubCell {
  double area, u1, u2;     // area, and centroid relative to the element's
  double s11, s22, s12;    // second moments about its own centroid
  double radial1, radial2; // the unit radial direction through its middle
  double depth, width;     // its radial depth and its arc length at the centroid
};

struct Element {
  double r_inner, r_outer, angle_from, angle_to;  // rad, angle_from < angle_to
  double area;                                    // A_e
  double x1, x2;                                  // centroid
  double s11, s22, s12;                           // integrals of u1^2, u2^2, u1 u2 over the element, u from the centroid
  std::vector<SubCell> cells;
  // The four corners (relative to the centroid) and the unit directions of
  // the two straight edges, so extent() needs no trigonometry.
  double corner1[4], corner2[4];
  double from1, from2, to1, to2;
  // The least and the greatest of a1 u1 + a2 u2 over the element (u from its centroid).
  std::pair<double, double> extent(double a1, double a2) const;
};

// The elements of a unit disc, ring by ring from the centre, each ring's
// sectors counter-clockwise from t1.
std::vector<Element> unit_disc_elements(int radial, int circumferential);

}  // namespace demcal::dem3d::flat_joint
