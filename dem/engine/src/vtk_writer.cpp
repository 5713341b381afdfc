#include "demcal/dem/vtk_writer.hpp"

#include <sstream>

#include "demcal/core/atomic_file.hpp"

namespace demcal::dem {

void write_vtk_disks(const World& world, const std::string& path) {
  const Bodies& b = world.bodies;
  const ContactSet& c = world.pairs();
  std::size_t bonds = 0;
  for (PairFlags f : c.flags) bonds += (f & kBonded) != 0;
  std::ostringstream out;
  out.precision(9);
  out << "# vtk DataFile Version 3.0\ndemcal disks at t = " << world.time_s() << " s\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << b.size() << " double\n";
  for (std::size_t i = 0; i < b.size(); ++i) out << b.x[i] << ' ' << b.y[i] << " 0\n";
  out << "VERTICES " << b.size() << ' ' << 2 * b.size() << '\n';
  for (std::size_t i = 0; i < b.size(); ++i) out << "1 " << i << '\n';
  out << "LINES " << bonds << ' ' << 3 * bonds << '\n';
  for (std::size_t k = 0; k < c.size(); ++k)
    if (c.flags[k] & kBonded) out << "2 " << c.i[k] << ' ' << c.j[k] << '\n';
  out << "POINT_DATA " << b.size() << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (double r : b.radius) out << r << '\n';
  out << "SCALARS clump_id int 1\nLOOKUP_TABLE default\n";
  for (std::int32_t id : b.clump) out << id << '\n';
  out << "VECTORS velocity double\n";
  for (std::size_t i = 0; i < b.size(); ++i) out << b.vx[i] << ' ' << b.vy[i] << " 0\n";
  out << "CELL_DATA " << b.size() + bonds << "\nSCALARS bond_intact int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < b.size(); ++i) out << "0\n";  // vertices are not bonds
  for (std::size_t k = 0; k < bonds; ++k) out << "1\n";
  write_file_atomically(path, out.str());
}

void write_vtk_breaks(const World& world, const std::string& path) {
  const std::vector<BreakEvent>& breaks = world.breaks();
  std::ostringstream out;
  out.precision(9);
  out << "# vtk DataFile Version 3.0\ndemcal bond breaks up to t = " << world.time_s() << " s\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << breaks.size() << " double\n";
  for (const BreakEvent& e : breaks) out << e.x_m << ' ' << e.y_m << " 0\n";
  out << "VERTICES " << breaks.size() << ' ' << 2 * breaks.size() << '\n';
  for (std::size_t i = 0; i < breaks.size(); ++i) out << "1 " << i << '\n';
  out << "POINT_DATA " << breaks.size() << "\nSCALARS mode int 1\nLOOKUP_TABLE default\n";
  for (const BreakEvent& e : breaks) out << static_cast<int>(e.mode) << '\n';
  out << "SCALARS time_s double 1\nLOOKUP_TABLE default\n";
  for (const BreakEvent& e : breaks) out << e.time_s << '\n';
  write_file_atomically(path, out.str());
}

void write_vtk_walls(const World& world, const std::string& path) {
  const std::vector<Wall>& walls = world.walls;
  std::ostringstream out;
  out.precision(9);
  out << "# vtk DataFile Version 3.0\ndemcal walls at t = " << world.time_s() << " s\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << 2 * walls.size() << " double\n";
  for (const Wall& w : walls) out << w.x0 << ' ' << w.y0 << " 0\n" << w.x1 << ' ' << w.y1 << " 0\n";
  out << "LINES " << walls.size() << ' ' << 3 * walls.size() << '\n';
  for (std::size_t k = 0; k < walls.size(); ++k) out << "2 " << 2 * k << ' ' << 2 * k + 1 << '\n';
  out << "CELL_DATA " << walls.size() << "\nSCALARS active int 1\nLOOKUP_TABLE default\n";
  for (const Wall& w : walls) out << (w.active ? 1 : 0) << '\n';
  out << "VECTORS force double\n";
  for (const Wall& w : walls) out << w.fx << ' ' << w.fy << " 0\n";
  write_file_atomically(path, out.str());
}

}  // namespace demcal::dem
