// The polygon in which a plane cuts an intersection of half-spaces (exact half-plane clipping).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// A convex polygon in a plane through `origin` with orthonormal in-plane axes `axis_u`, `axis_v`
/// (right-handed with the plane normal: axis_u × axis_v = normal). Vertices are 2D plane
/// coordinates (m), counter-clockwise about the normal.
struct SlicePolygon {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  std::vector<Eigen::Vector2d> vertices;

  double area() const;                      ///< (m^2)
  Eigen::Vector2d centroid_2d() const;      ///< area centroid in plane coordinates (m)
  Eigen::Vector3d to_world(const Eigen::Vector2d& p) const { return origin + p.x() * axis_u + p.y() * axis_v; }
};

/// Orthonormal in-plane axes for a unit normal (a fixed, continuous-almost-everywhere choice).
void plane_axes(const Eigen::Vector3d& normal, Eigen::Vector3d& axis_u, Eigen::Vector3d& axis_v);

/// The polygon {x in plane(origin, normal) : n_j·x <= d_j for all j}. `extent` (m) must exceed the
/// polygon's radius about `origin` (e.g. the sum of the two blocks' bounding diameters). Planes
/// parallel to the slice keep or remove the whole polygon, exactly.
SlicePolygon slice_halfspaces(std::span<const Halfspace> planes, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& normal, double extent);

}  // namespace blockdem
