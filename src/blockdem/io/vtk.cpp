// Legacy VTK POLYDATA writer.
#include "blockdem/io/vtk.hpp"

#include <sstream>
#include <stdexcept>

#include "blockdem/io/atomic_file.hpp"

namespace blockdem {

void write_vtk_blocks(const std::filesystem::path& path, const World& world) {
  // Built in memory and written atomically: a reader never sees half a file.
  std::ostringstream out;
  out.precision(10);
  std::size_t points = 0, polys = 0, poly_ints = 0;
  for (const auto& b : world.blocks()) {
    points += b.shape.vertices().size();
    polys += b.shape.faces().size();
    for (const auto& f : b.shape.faces()) poly_ints += f.vertices.size() + 1;
  }
  out << "# vtk DataFile Version 3.0\nblockdem blocks\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << points << " double\n";
  for (const auto& b : world.blocks()) {
    for (const auto& v : b.shape.vertices()) {
      const Eigen::Vector3d w = b.to_world(v) + world.settings().origin;  // user's coordinates
      out << w.x() << " " << w.y() << " " << w.z() << "\n";
    }
  }
  out << "POLYGONS " << polys << " " << poly_ints << "\n";
  std::size_t base = 0;
  for (const auto& b : world.blocks()) {
    for (const auto& f : b.shape.faces()) {
      out << f.vertices.size();
      for (int v : f.vertices) out << " " << base + static_cast<std::size_t>(v);
      out << "\n";
    }
    base += b.shape.vertices().size();
  }
  out << "CELL_DATA " << polys << "\nSCALARS block_index int 1\nLOOKUP_TABLE default\n";
  for (const auto& b : world.blocks()) {
    for (std::size_t f = 0; f < b.shape.faces().size(); ++f) out << b.index << "\n";
  }
  out << "VECTORS displacement_m double\n";
  for (const auto& b : world.blocks()) {
    const Eigen::Vector3d d = b.position - b.initial_position;
    for (std::size_t f = 0; f < b.shape.faces().size(); ++f)
      out << d.x() << " " << d.y() << " " << d.z() << "\n";
  }
  out << "VECTORS velocity_m_s double\n";
  for (const auto& b : world.blocks()) {
    for (std::size_t f = 0; f < b.shape.faces().size(); ++f)
      out << b.velocity.x() << " " << b.velocity.y() << " " << b.velocity.z() << "\n";
  }
  write_file_atomically(path, out.str());
}

void write_vtk_contacts(const std::filesystem::path& path, const World& world) {
  // Built in memory and written atomically: a reader never sees half a file.
  std::ostringstream out;
  out.precision(10);
  const auto contacts = world.contacts();
  out << "# vtk DataFile Version 3.0\nblockdem contacts\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << contacts.size() << " double\n";
  for (const Contact* c : contacts) {
    const Eigen::Vector3d p = c->geometry.point + world.settings().origin;
    out << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  out << "VERTICES " << contacts.size() << " " << 2 * contacts.size() << "\n";
  for (std::size_t i = 0; i < contacts.size(); ++i) out << "1 " << i << "\n";
  out << "POINT_DATA " << contacts.size() << "\n";
  out << "VECTORS normal double\n";
  for (const Contact* c : contacts) {
    const auto& n = c->geometry.normal;
    out << n.x() << " " << n.y() << " " << n.z() << "\n";
  }
  out << "VECTORS force_on_b_N double\n";
  for (const Contact* c : contacts) {
    const Eigen::Vector3d f = c->force_on_b();
    out << f.x() << " " << f.y() << " " << f.z() << "\n";
  }
  out << "SCALARS normal_force_N double 1\nLOOKUP_TABLE default\n";
  for (const Contact* c : contacts) out << c->normal_force << "\n";
  out << "SCALARS overlap_m double 1\nLOOKUP_TABLE default\n";
  for (const Contact* c : contacts) out << c->geometry.overlap << "\n";
  out << "SCALARS area_m2 double 1\nLOOKUP_TABLE default\n";
  for (const Contact* c : contacts) out << c->geometry.area << "\n";
  write_file_atomically(path, out.str());
}

}  // namespace blockdem
