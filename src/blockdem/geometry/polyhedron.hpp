// Convex polyhedra given by planes: vertices, ordered faces, exact volume, centroid and inertia.
#pragma once

#include <Eigen/Core>
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
class Polyhedron {
 public:
  /// From planes (unit outward normals; redundant planes are dropped).
  static Polyhedron from_planes(std::span<const Halfspace> planes);
  /// Axis-aligned box centred at the origin with the given full side lengths (m).
  static Polyhedron box(const Eigen::Vector3d& size);
  /// Convex hull of points; every point must be a vertex of (or lie on) the hull, otherwise the
  /// input is rejected as non-convex.
  static Polyhedron from_vertices(std::span<const Eigen::Vector3d> points);

  const std::vector<Halfspace>& planes() const { return planes_; }
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  const std::vector<Face>& faces() const { return faces_; }

  double volume() const { return volume_; }                      ///< (m^3)
  const Eigen::Vector3d& centroid() const { return centroid_; }  ///< (m)
  /// Inertia tensor about the centroid for unit density (m^5; multiply by density for kg m^2).
  const Eigen::Matrix3d& unit_inertia() const { return unit_inertia_; }
  /// Largest distance from the centroid to a vertex (m).
  double bounding_radius() const { return bounding_radius_; }
  /// Area of face f (m^2).
  double face_area(int f) const;

  /// The same solid moved rigidly: x -> R x + t.
  Polyhedron transformed(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) const;

 private:
  void build(std::vector<Halfspace> planes);

  std::vector<Halfspace> planes_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Face> faces_;
  double volume_ = 0.0;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d unit_inertia_ = Eigen::Matrix3d::Zero();
  double bounding_radius_ = 0.0;
};

/// Area-weighted polygon area of ordered 3D points (m^2).
double polygon_area(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& normal);

}  // namespace blockdem
