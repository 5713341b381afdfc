#include "demcal/dem/lammps_data.hpp"

#include <cstdio>
#include <sstream>

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/error.hpp"

namespace demcal::dem {

namespace {

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

void write_lammps_data(const Specimen& s, const std::string& path, const std::string& title) {
  if (s.size() == 0) throw Error(path + ": the specimen has no disks");
  std::ostringstream out;
  out << "LAMMPS data file: " << title << " (2D disks, thickness " << number(s.thickness_m)
      << " m: after read_data, set group all density/disc " << number(s.density_kg_m3 * s.thickness_m) << ")\n\n";
  out << s.size() << " atoms\n1 atom types\n\n";
  // Room around the specimen: LAMMPS drops atoms outside a fixed box.
  double margin = 0;
  for (double r : s.radius) margin = std::max(margin, r);
  out << number(-2 * margin) << " " << number(s.width_m + 2 * margin) << " xlo xhi\n";
  out << number(-2 * margin) << " " << number(s.height_m + 2 * margin) << " ylo yhi\n";
  out << number(-0.5 * s.thickness_m) << " " << number(0.5 * s.thickness_m) << " zlo zhi\n\n";
  out << "Atoms # sphere\n\n";
  for (std::size_t i = 0; i < s.size(); ++i)
    out << i + 1 << " 1 " << number(2 * s.radius[i]) << " " << number(s.density_kg_m3) << " " << number(s.x[i]) << " "
        << number(s.y[i]) << " 0\n";
  write_file_atomically(path, out.str());
}

}  // namespace demcal::dem
