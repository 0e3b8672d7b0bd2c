// VTK XML writer: UnstructuredGrid with raw appended data (header_type UInt64), as described in
// "VTK File Formats" of the VTK User's Guide (Kitware, 11th ed., 2010, ch. 19, XML formats).
#include "blockdem/io/vtu.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/numerics/units.hpp"
#include "blockdem/world/pair_owner.hpp"

namespace blockdem {
namespace {

// One data array of the appended block: its XML attributes and its bytes.
struct Array {
  std::string name, type;
  int components = 1;
  std::string bytes;
};

template <class T>
Array array(const std::string& name, const std::string& type, int components,
            const std::vector<T>& values) {
  Array a{name, type, components, std::string(values.size() * sizeof(T), '\0')};
  if (!values.empty()) std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
  return a;
}

Array vectors(const std::string& name, const std::vector<Eigen::Vector3d>& values) {
  std::vector<double> flat;
  flat.reserve(3 * values.size());
  for (const auto& v : values) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  return array(name, "Float64", 3, flat);
}

// Strings: each followed by a NUL, as VTK's XML readers expect for a String array.
Array strings(const std::string& name, const std::vector<std::string>& values) {
  Array a{name, "String", 1, {}};
  for (const auto& s : values) {
    a.bytes += s;
    a.bytes.push_back('\0');
  }
  return a;
}

void write_arrays(std::ostream& out, const std::vector<Array>& arrays, std::uint64_t& offset) {
  for (const Array& a : arrays) {
    out << "        <DataArray type=\"" << a.type << "\" Name=\"" << a.name
        << "\" NumberOfComponents=\"" << a.components << "\" format=\"appended\" offset=\""
        << offset << "\"/>\n";
    offset += sizeof(std::uint64_t) + a.bytes.size();
  }
}

// A grid's contents: counts, point data, cell data, points and cells (connectivity, offsets,
// types and, for polyhedra, faces and faceoffsets).
struct Grid {
  std::size_t points = 0, cells = 0;
  std::vector<Array> point_data, cell_data;
  Array coordinates;
  std::vector<Array> topology;
};

// Writes the grid: its model time as the field TimeValue (the name ParaView reads a frame's time
// from when a .vtu is opened alone), point data, cell data, points, cells, then the appended
// bytes. Built in memory and written atomically: a reader never sees half a file.
void write_grid(const std::filesystem::path& path, double time, const Grid& g) {
  std::ostringstream out(std::ios::binary);
  const char* order = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\""
      << order << "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
      << "format=\"ascii\">" << std::setprecision(17) << time << "</DataArray>\n"
      << "    </FieldData>\n    <Piece NumberOfPoints=\"" << g.points << "\" NumberOfCells=\""
      << g.cells << "\">\n";
  std::uint64_t offset = 0;
  out << "      <PointData>\n";
  write_arrays(out, g.point_data, offset);
  out << "      </PointData>\n      <CellData>\n";
  write_arrays(out, g.cell_data, offset);
  out << "      </CellData>\n      <Points>\n";
  write_arrays(out, {g.coordinates}, offset);
  out << "      </Points>\n      <Cells>\n";
  write_arrays(out, g.topology, offset);
  out << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n"
      << "   _";
  auto bytes = [&out](const Array& a) {
    const std::uint64_t n = a.bytes.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof n);
    out.write(a.bytes.data(), static_cast<std::streamsize>(a.bytes.size()));
  };
  for (const Array& a : g.point_data) bytes(a);
  for (const Array& a : g.cell_data) bytes(a);
  bytes(g.coordinates);
  for (const Array& a : g.topology) bytes(a);
  out << "\n  </AppendedData>\n</VTKFile>\n";
  write_file_atomically(path, out.str());
}

// The parallel index of a distributed frame (VTK User's Guide, ch. 19, "Parallel XML file
// formats"): the arrays' names, types and components, and the pieces' files (relative to the
// index's folder). The model time is in each piece's TimeValue.
void write_parallel_index(const std::filesystem::path& path, const Grid& g,
                          const std::vector<std::string>& pieces) {
  std::ostringstream out;
  const char* order = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  auto declare = [&out](const char* tag, const std::vector<Array>& arrays) {
    out << "    <" << tag << ">\n";
    for (const Array& a : arrays)
      out << "      <PDataArray type=\"" << a.type << "\" Name=\"" << a.name
          << "\" NumberOfComponents=\"" << a.components << "\"/>\n";
    out << "    </" << tag << ">\n";
  };
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
      << "byte_order=\"" << order << "\" header_type=\"UInt64\">\n"
      << "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  declare("PPointData", g.point_data);
  declare("PCellData", g.cell_data);
  declare("PPoints", {g.coordinates});
  for (const std::string& piece : pieces) out << "    <Piece Source=\"" << piece << "\"/>\n";
  out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file_atomically(path, out.str());
}

constexpr std::uint8_t kVtkVertex = 1;
constexpr std::uint8_t kVtkPolyhedron = 42;

}  // namespace

ContactStatus contact_status(const Contact& c) {
  if (c.shear.broken()) return ContactStatus::broken;
  if (c.sliding) return ContactStatus::sliding;
  if (!(c.normal_force > 0.0)) return ContactStatus::open;
  return ContactStatus::closed;
}

namespace {

// Blocks `which` (indices, in increasing order) as polyhedron cells at the world's level state.
Grid block_grid(const World& world, int stage, const std::vector<int>& which) {
  std::vector<Eigen::Vector3d> coordinates, displacement, velocity, rotation, spin;
  std::vector<std::int64_t> connectivity, offsets, faces, face_offsets;
  std::vector<std::uint8_t> types;
  std::vector<std::int32_t> ids, stages;
  std::vector<std::string> names, groups;
  const Eigen::Vector3d& origin = world.settings().origin;  // points out in user coordinates
  for (int index : which) {
    const Block& b = world.blocks()[static_cast<std::size_t>(index)];
    const World::LevelState s = world.level_state(b.index);
    const auto base = static_cast<std::int64_t>(coordinates.size());
    for (std::size_t v = 0; v < b.shape.vertices().size(); ++v) {
      coordinates.push_back(s.position + s.orientation * b.shape.vertices()[v] + origin);
      connectivity.push_back(base + static_cast<std::int64_t>(v));
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(kVtkPolyhedron);
    // Faces: their count, then per face its vertex count and global point ids (outward order).
    faces.push_back(static_cast<std::int64_t>(b.shape.faces().size()));
    for (const auto& f : b.shape.faces()) {
      faces.push_back(static_cast<std::int64_t>(f.vertices.size()));
      for (int v : f.vertices) faces.push_back(base + v);
    }
    face_offsets.push_back(static_cast<std::int64_t>(faces.size()));
    ids.push_back(b.index);
    names.push_back(b.name);
    groups.push_back(b.group());
    stages.push_back(stage);
    displacement.push_back(s.position - b.initial_position);
    velocity.push_back(s.velocity);
    const Eigen::AngleAxisd turn(s.orientation * b.initial_orientation.conjugate());
    const double angle = turn.angle() > kPi ? turn.angle() - 2 * kPi : turn.angle();
    rotation.push_back(angle * turn.axis());
    spin.push_back(s.angular_velocity);
  }
  Grid g;
  g.points = coordinates.size();
  g.cells = which.size();
  g.cell_data = {array("block_id", "Int32", 1, ids),
                 strings("name", names),
                 strings("group", groups),
                 array("stage", "Int32", 1, stages),
                 vectors("displacement", displacement),
                 vectors("velocity", velocity),
                 vectors("rotation", rotation),
                 vectors("angular_velocity", spin)};
  g.coordinates = vectors("Points", coordinates);
  g.topology = {array("connectivity", "Int64", 1, connectivity),
                array("offsets", "Int64", 1, offsets), array("types", "UInt8", 1, types),
                array("faces", "Int64", 1, faces), array("faceoffsets", "Int64", 1, face_offsets)};
  return g;
}

// Contacts as vertices at their force points.
Grid contact_grid(const World& world, const std::vector<const Contact*>& contacts) {
  std::vector<Eigen::Vector3d> points, normal, shear;
  std::vector<std::int32_t> a, b, status;
  std::vector<double> force, stress, closure, area;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  const Eigen::Vector3d& origin = world.settings().origin;  // points out in user coordinates
  for (const Contact* c : contacts) {
    connectivity.push_back(static_cast<std::int64_t>(points.size()));
    offsets.push_back(static_cast<std::int64_t>(points.size()) + 1);
    types.push_back(kVtkVertex);
    points.push_back(c->force_point() + origin);
    a.push_back(c->a);
    b.push_back(c->b);
    normal.push_back(c->geometry.normal);
    force.push_back(c->normal_force);
    shear.push_back(c->shear.force);
    stress.push_back(c->normal_stress);
    closure.push_back(c->geometry.overlap);
    area.push_back(c->geometry.area);
    status.push_back(static_cast<std::int32_t>(contact_status(*c)));
  }
  Grid g;
  g.points = points.size();
  g.cells = points.size();
  g.point_data = {array("block_a", "Int32", 1, a),
                  array("block_b", "Int32", 1, b),
                  vectors("normal", normal),
                  array("normal_force", "Float64", 1, force),
                  vectors("shear_force", shear),
                  array("normal_stress", "Float64", 1, stress),
                  array("closure", "Float64", 1, closure),
                  array("area", "Float64", 1, area),
                  array("status", "Int32", 1, status)};
  g.coordinates = vectors("Points", points);
  g.topology = {array("connectivity", "Int64", 1, connectivity),
                array("offsets", "Int64", 1, offsets), array("types", "UInt8", 1, types)};
  return g;
}

// The bolts as lines: one cell per tendon element (a point-anchored bolt is one element), from
// its points in the blocks that hold them at their present poses.
Grid bolt_grid(const World& world) {
  constexpr std::uint8_t kVtkLine = 3;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::int32_t> bolt_id, state;
  std::vector<double> force;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  const auto& blocks = world.blocks();
  const Eigen::Vector3d& origin = world.settings().origin;
  const auto at = [&](const BoltTie& t) -> Eigen::Vector3d {
    return blocks[static_cast<std::size_t>(t.block)].to_world(t.body_point) + origin;
  };
  for (std::size_t k = 0; k < world.bolts().size(); ++k) {
    const Bolt& bolt = world.bolts()[k];
    const bool removed = bolt.state == Bolt::State::removed;
    const std::size_t elements = bolt.spec.grouted() ? bolt.tendon.elements.size() : 1;
    for (std::size_t e = 0; e < elements; ++e) {
      // A grouted element's ends: its two springs' points; a removed bolt at installation.
      const BoltTie& t0 = bolt.ties[bolt.spec.grouted() ? 2 * e : 0];
      const BoltTie& t1 = bolt.ties[bolt.spec.grouted() ? 2 * e + 1 : 1];
      connectivity.push_back(static_cast<std::int64_t>(points.size()));
      connectivity.push_back(static_cast<std::int64_t>(points.size()) + 1);
      points.push_back(removed ? Eigen::Vector3d(t0.installed + origin) : at(t0));
      points.push_back(removed ? Eigen::Vector3d(t1.installed + origin) : at(t1));
      offsets.push_back(static_cast<std::int64_t>(points.size()));
      types.push_back(kVtkLine);
      bolt_id.push_back(static_cast<std::int32_t>(k));
      state.push_back(static_cast<std::int32_t>(bolt.state));
      force.push_back(!bolt.active()        ? 0.0
                      : bolt.spec.grouted() ? bolt.tendon.elements[e].force
                                            : bolt.axial_force);
    }
  }
  Grid g;
  g.points = points.size();
  g.cells = types.size();
  g.cell_data = {array("bolt", "Int32", 1, bolt_id), array("axial_force", "Float64", 1, force),
                 array("state", "Int32", 1, state)};
  g.coordinates = vectors("Points", points);
  g.topology = {array("connectivity", "Int64", 1, connectivity),
                array("offsets", "Int64", 1, offsets), array("types", "UInt8", 1, types)};
  return g;
}

}  // namespace

void write_vtu_bolts(const std::filesystem::path& path, const World& world) {
  write_grid(path, world.level_time(), bolt_grid(world));
}

void write_vtu_blocks(const std::filesystem::path& path, const World& world, int stage) {
  std::vector<int> all(world.blocks().size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  write_grid(path, world.level_time(), block_grid(world, stage, all));
}

void write_vtu_contacts(const std::filesystem::path& path, const World& world) {
  write_grid(path, world.level_time(), contact_grid(world, world.contacts()));
}

std::size_t write_vtu_block_piece(const std::filesystem::path& path, const World& world, int stage,
                                  int process) {
  const std::vector<int>& owners = world.block_owners();
  std::vector<int> mine;
  for (std::size_t i = 0; i < world.blocks().size(); ++i) {
    if ((owners.empty() ? 0 : owners[i]) == process) mine.push_back(static_cast<int>(i));
  }
  write_grid(path, world.level_time(), block_grid(world, stage, mine));
  return mine.size();
}

std::size_t write_vtu_contact_piece(const std::filesystem::path& path, const World& world,
                                    int process) {
  const std::vector<int>& owners = world.block_owners();
  std::vector<const Contact*> mine;
  for (const Contact* c : world.counted_contacts()) {
    const bool a_moves = world.blocks()[static_cast<std::size_t>(c->a)].is_dynamic();
    const bool b_moves = world.blocks()[static_cast<std::size_t>(c->b)].is_dynamic();
    if (pair_owner_process(owners, c->a, a_moves, c->b, b_moves) == process) mine.push_back(c);
  }
  write_grid(path, world.level_time(), contact_grid(world, mine));
  return mine.size();
}

void write_pvtu_blocks(const std::filesystem::path& path, const World& world,
                       const std::vector<std::string>& pieces) {
  write_parallel_index(path, block_grid(world, 0, {}), pieces);
}

void write_pvtu_contacts(const std::filesystem::path& path, const World& world,
                         const std::vector<std::string>& pieces) {
  write_parallel_index(path, contact_grid(world, {}), pieces);
}

void PvdCollection::add(double time, const std::string& file) {
  frames_.emplace_back(time, file);
  std::ostringstream xml;
  xml.precision(17);
  xml << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n"
      << "  <Collection>\n";
  for (const auto& [t, f] : frames_)
    xml << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << f << "\"/>\n";
  xml << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, xml.str());  // a reader never sees half a file
}

}  // namespace blockdem
