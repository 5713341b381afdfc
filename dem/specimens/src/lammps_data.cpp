#include "demcal/dem/lammps_data.hpp"

#include <algorithm>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal::dem {

void write_lammps_data(const Specimen& s, const std::string& path, const std::string& title) {
  if (s.size() == 0) throw Error(path + ": the specimen has no disks");
  std::ostringstream out;
  out << "LAMMPS data file: " << title << " (2D disks, thickness " << format_double(s.thickness_m)
      << " m: after read_data, set group all density/disc " << format_double(s.density_kg_m3 * s.thickness_m) << ")\n\n";
  out << s.size() << " atoms\n1 atom types\n\n";
  // Room around the specimen: LAMMPS drops atoms outside a fixed box.
  double margin = 0;
  for (double r : s.radius) margin = std::max(margin, r);
  out << format_double(-2 * margin) << " " << format_double(s.width_m + 2 * margin) << " xlo xhi\n";
  out << format_double(-2 * margin) << " " << format_double(s.height_m + 2 * margin) << " ylo yhi\n";
  out << format_double(-0.5 * s.thickness_m) << " " << format_double(0.5 * s.thickness_m) << " zlo zhi\n\n";
  out << "Atoms # sphere\n\n";
  for (std::size_t i = 0; i < s.size(); ++i)
    out << i + 1 << " 1 " << format_double(2 * s.radius[i]) << " " << format_double(s.density_kg_m3) << " " << format_double(s.x[i]) << " "
        << format_double(s.y[i]) << " 0\n";
  write_file_atomically(path, out.str());
}

}  // namespace demcal::dem
