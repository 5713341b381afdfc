#include <cmath>

#include <Eigen/Dense>

#include "demcal/core/error.hpp"
#include "demcal/dem3d/clump.hpp"

namespace demcal::dem3d {

ClumpShape clump_of_spheres(const std::vector<Vec3>& centres, const std::vector<double>& radii, double density) {
  if (centres.empty() || centres.size() != radii.size()) throw Error("a clump needs one radius per sphere");
  ClumpShape out;
  std::vector<double> masses;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    if (!(radii[k] > 0)) throw Error("a clump's spheres need positive radii");
    masses.push_back(density * 4.0 / 3.0 * M_PI * radii[k] * radii[k] * radii[k]);
    out.mass_kg += masses.back();
    out.centre_m = out.centre_m + masses.back() * centres[k];
  }
  out.centre_m = (1.0 / out.mass_kg) * out.centre_m;
  // Each sphere's own 2/5 m r^2 plus the parallel-axis term m (|d|^2 I - d d^T).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const Vec3 d = centres[k] - out.centre_m;
    const Eigen::Vector3d v(d.x, d.y, d.z);
    inertia += masses[k] * (0.4 * radii[k] * radii[k] + v.squaredNorm()) * Eigen::Matrix3d::Identity() -
               masses[k] * v * v.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
  const Eigen::Quaterniond q(axes);
  out.principal_inertia_kg_m2 = {solver.eigenvalues()(0), solver.eigenvalues()(1), solver.eigenvalues()(2)};
  out.orientation = normalised({q.w(), q.x(), q.y(), q.z()});
  return out;
}

}  // namespace demcal::dem3d
