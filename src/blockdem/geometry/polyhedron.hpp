// Convex polyhedra given by planes: vertices, ordered faces, exact volume, centroid and inertia.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// One face: the plane index it lies on and its vertex indices in counter-clockwise order seen
/// from outside (right-handed about the outward normal).
struct Face {
  int plane = -1;
  std::vector<int> vertices;
};

/// A bounded convex polyhedron {x : n_i · x <= d_i}. Construction derives vertices and faces,
/// drops redundant planes and computes mass properties for unit density exactly (signed
/// tetrahedra from an interior point). Throws GeometryError on a bad shape.
/// A polyhedron is immutable: copies share one set of planes, vertices and faces (a copy costs
/// a reference count), so blocks of one shape hold its data once.
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
  Polyhedron(const Polyhedron&) = default;
  Polyhedron& operator=(const Polyhedron&) = default;
  // A move shares too: the source keeps its shape and stays usable.
  Polyhedron(Polyhedron&& other) noexcept : data_(other.data_) {}
  Polyhedron& operator=(Polyhedron&& other) noexcept {
    data_ = other.data_;
    return *this;
  }

  const std::vector<Halfspace>& planes() const { return data_->planes; }
  const std::vector<Eigen::Vector3d>& vertices() const { return data_->vertices; }
  const std::vector<Face>& faces() const { return data_->faces; }

  double volume() const { return data_->volume; }                      ///< (m^3)
  const Eigen::Vector3d& centroid() const { return data_->centroid; }  ///< (m)
  /// Inertia tensor about the centroid for unit density (m^5; multiply by density for kg m^2).
  const Eigen::Matrix3d& unit_inertia() const { return data_->unit_inertia; }
  /// Largest distance from the centroid to a vertex (m).
  double bounding_radius() const { return data_->bounding_radius; }
  /// Whether this and `other` share their data (one is a copy of the other).
  bool shares_data_with(const Polyhedron& other) const { return data_ == other.data_; }
  /// Where the shape's record lies, for a prefetch (a hint: it changes no result).
  const void* record_address() const { return data_.get(); }
  /// Area of face f (m^2).
  double face_area(int f) const;

  /// The same solid moved rigidly: x -> R x + t.
  Polyhedron transformed(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) const;

 private:
  struct Data {
    std::vector<Halfspace> planes;
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Face> faces;
    double volume = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Matrix3d unit_inertia = Eigen::Matrix3d::Zero();
    double bounding_radius = 0.0;
  };
  static std::shared_ptr<const Data> build(std::vector<Halfspace> planes, bool known_closed);

  std::shared_ptr<const Data> data_;  ///< never null; shared by copies
};

/// Area-weighted polygon area of ordered 3D points (m^2).
double polygon_area(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& normal);

}  // namespace blockdem
