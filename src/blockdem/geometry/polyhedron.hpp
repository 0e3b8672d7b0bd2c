// Convex polyhedra given by planes: vertices, ordered faces, exact volume, centroid and inertia.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// One face: the plane index it lies on and its vertex indices in counter-clockwise order seen
/// from outside (right-handed about the outward normal).
/// The indices live in the polyhedron's record, which the face must not outlive.
struct Face {
  int plane = -1;
  std::span<const int> vertices;
};

/// A bounded convex polyhedron {x : n_i · x <= d_i}. Construction derives vertices and faces,
/// drops redundant planes and computes mass properties for unit density exactly (signed
/// tetrahedra from an interior point). Throws GeometryError on a bad shape.
/// A polyhedron is immutable: copies share one set of planes, vertices and faces (a copy costs
/// a reference count), so blocks of one shape hold its data once. That set is one allocation
/// (a rock mass has a shape per block: ten allocations per shape were a quarter more memory).
class Polyhedron {
 public:
  /// From planes (unit outward normals; redundant planes are dropped).
  static Polyhedron from_planes(std::span<const Halfspace> planes);
  /// As from_planes, for planes known to enclose a bounded solid (a rigid motion of a
  /// polyhedron, the faces of a convex cell cut from one): the same shape, bit for bit, without
  /// the test for an empty or unbounded set (a vertex enumeration with six far planes added,
  /// most of the cost of from_planes). The checks for a degenerate solid stay.
  static Polyhedron from_closed_planes(std::span<const Halfspace> planes);
  /// Axis-aligned box centred at the origin with the given full side lengths (m).
  static Polyhedron box(const Eigen::Vector3d& size);
  /// Convex hull of points; every point must be a vertex of (or lie on) the hull, otherwise the
  /// input is rejected as non-convex.
  static Polyhedron from_vertices(std::span<const Eigen::Vector3d> points);

  /// An empty polyhedron (no planes, zero volume), to be assigned a shape.
  Polyhedron();
  Polyhedron(const Polyhedron& other) noexcept : data_(other.data_) { data_->share(); }
  Polyhedron& operator=(const Polyhedron& other) noexcept {
    other.data_->share();
    data_->release();
    data_ = other.data_;
    return *this;
  }
  // A move shares too: the source keeps its shape and stays usable.
  Polyhedron(Polyhedron&& other) noexcept : Polyhedron(other) {}
  Polyhedron& operator=(Polyhedron&& other) noexcept { return *this = other; }
  ~Polyhedron() { data_->release(); }

  // Views into the shared record: they live as long as this polyhedron or a copy of it (so a
  // temporary's are refused: copy them out of a named one).
  std::span<const Halfspace> planes() const& { return {data_->planes(), data_->n_planes}; }
  std::span<const Eigen::Vector3d> vertices() const& {
    return {data_->vertices(), data_->n_vertices};
  }
  std::span<const Face> faces() const& { return {data_->faces(), data_->n_faces}; }
  std::span<const Halfspace> planes() const&& = delete;
  std::span<const Eigen::Vector3d> vertices() const&& = delete;
  std::span<const Face> faces() const&& = delete;

  double volume() const { return data_->volume; }                      ///< (m^3)
  const Eigen::Vector3d& centroid() const { return data_->centroid; }  ///< (m)
  /// Inertia tensor about the centroid for unit density (m^5; multiply by density for kg m^2).
  const Eigen::Matrix3d& unit_inertia() const { return data_->unit_inertia; }
  /// Largest distance from the centroid to a vertex (m).
  double bounding_radius() const { return data_->bounding_radius; }
  /// Whether this and `other` share their data (one is a copy of the other).
  bool shares_data_with(const Polyhedron& other) const { return data_ == other.data_; }
  /// Where the shape's record lies, for a prefetch (a hint: it changes no result).
  const void* record_address() const { return data_; }
  /// Area of face f (m^2).
  double face_area(int f) const;

  /// The same solid moved rigidly: x -> R x + t.
  Polyhedron transformed(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) const;

 private:
  /// The shape's record: this header, then its planes, vertices, faces and the faces' vertex
  /// indices, in one allocation (polyhedron.cpp, `pack`), freed with the last copy.
  struct Data {
    mutable std::atomic<std::size_t> references{1};
    std::uint32_t n_planes = 0, n_vertices = 0, n_faces = 0, n_indices = 0;
    double volume = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Matrix3d unit_inertia = Eigen::Matrix3d::Zero();
    double bounding_radius = 0.0;

    // The arrays after the header, each aligned for its type (the header's size is a multiple
    // of 8, as are a plane's, a vertex's and a face's).
    const Halfspace* planes() const { return reinterpret_cast<const Halfspace*>(this + 1); }
    const Eigen::Vector3d* vertices() const {
      return reinterpret_cast<const Eigen::Vector3d*>(planes() + n_planes);
    }
    const Face* faces() const { return reinterpret_cast<const Face*>(vertices() + n_vertices); }
    const int* indices() const { return reinterpret_cast<const int*>(faces() + n_faces); }

    void share() const { references.fetch_add(1, std::memory_order_relaxed); }
    /// The last copy's release frees the record (the empty shape's is never released to zero).
    void release() const;
  };
  static const Data* build(std::vector<Halfspace> planes, bool known_closed);
  /// Takes the record's one reference.
  explicit Polyhedron(const Data* data) : data_(data) {}

  const Data* data_;  ///< never null; shared by copies
};

/// The planes of `shape` as a list of its own (to edit, or to keep past a temporary shape).
inline std::vector<Halfspace> copy_planes(const Polyhedron& shape) {
  return {shape.planes().begin(), shape.planes().end()};
}

/// Area-weighted polygon area of ordered 3D points (m^2).
double polygon_area(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& normal);

}  // namespace blockdem
