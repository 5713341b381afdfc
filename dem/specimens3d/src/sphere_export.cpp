#include "demcal/dem3d/sphere_export.hpp"

#include <algorithm>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem3d {
namespace {

void require_spheres(const SphereSpecimen& s, const std::string& path) {
  if (s.size() == 0) throw Error(path + ": the specimen has no spheres");
}

}  // namespace

void write_lammps_data(const SphereSpecimen& s, const std::string& path, const std::string& title) {
  require_spheres(s, path);
  double low[3] = {1e300, 1e300, 1e300}, high[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double p[3] = {s.x[i], s.y[i], s.z[i]};
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], p[a] - s.radius[i]);
      high[a] = std::max(high[a], p[a] + s.radius[i]);
    }
  }
  std::ostringstream out;
  out << "LAMMPS data file: " << title << " (3D spheres)\n\n" << s.size() << " atoms\n1 atom types\n\n";
  const char* names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a)
    out << format_double(low[a]) << ' ' << format_double(high[a]) << ' ' << names[a] << "lo " << names[a] << "hi\n";
  out << "\nAtoms # sphere\n\n";
  for (std::size_t i = 0; i < s.size(); ++i)
    out << i + 1 << " 1 " << format_double(2 * s.radius[i]) << ' ' << format_double(s.density_kg_m3) << ' ' << format_double(s.x[i]) << ' '
        << format_double(s.y[i]) << ' ' << format_double(s.z[i]) << '\n';
  write_file_atomically(path, out.str());
}

void write_sphere_text(const SphereSpecimen& s, const std::string& path, const std::string& title) {
  require_spheres(s, path);
  std::ostringstream out;
  out << "# " << title << ": " << s.size() << " spheres, density " << format_double(s.density_kg_m3)
      << " kg/m3, porosity " << format_double(s.porosity) << "\n# x y z r (m)\n";
  for (std::size_t i = 0; i < s.size(); ++i)
    out << format_double(s.x[i]) << ' ' << format_double(s.y[i]) << ' ' << format_double(s.z[i]) << ' ' << format_double(s.radius[i]) << '\n';
  write_file_atomically(path, out.str());
}

}  // namespace demcal::dem3d
