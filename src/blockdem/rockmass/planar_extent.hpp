// The extent of a non-persistent joint or of an excavation's outline facet in its plane (a disc
// or a convex polygon), and how a block's section by that plane overlaps it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

struct PlanarExtent {
  Halfspace plane;                                   ///< the joint's plane
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< origin of the in-plane axes (m)
  Eigen::Vector3d axis1 = Eigen::Vector3d::UnitX();  ///< in-plane unit axes, axis1 x axis2 =
  Eigen::Vector3d axis2 = Eigen::Vector3d::UnitY();  ///< the plane's normal (-)
  bool disc = false;
  double radius = 0.0;                   ///< disc (m)
  std::vector<Eigen::Vector2d> polygon;  ///< convex polygon in (axis1, axis2) about centre (m)
};

enum class Overlap {
  none,     ///< the section and the extent share no area
  partial,  ///< they share area, and part of the section lies outside the extent
  inside,   ///< the section lies wholly inside the extent
};

/// How a planar convex polygon on the extent's plane (e.g. a block's section) overlaps the
/// extent; `tol` (m) is the length below which a shared strip counts as no overlap.
Overlap overlap(const std::vector<Eigen::Vector3d>& section, const PlanarExtent& extent,
                double tol);

/// Area of a convex polygon clipped by another convex polygon, both counter-clockwise (m^2).
double clipped_area(std::vector<Eigen::Vector2d> subject, const std::vector<Eigen::Vector2d>& clip);

/// Signed area of a 2D polygon (positive counter-clockwise) (m^2).
double signed_area(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace blockdem
