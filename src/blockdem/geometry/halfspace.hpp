// A closed half-space n·x <= d with a unit outward normal: the building block of convex blocks.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace blockdem {

/// The set {x : normal · x <= offset}. `normal` is a unit vector (dimensionless), `offset` in m.
struct Halfspace {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit outward normal (-)
  double offset = 0.0;  ///< signed distance of the plane from the origin (m)

  /// Signed distance of x outside the plane: negative inside, zero on it, positive outside (m).
  double signed_distance(const Eigen::Vector3d& x) const { return normal.dot(x) - offset; }
  /// Slack d - n·x: positive inside (m).
  double slack(const Eigen::Vector3d& x) const { return offset - normal.dot(x); }
};

}  // namespace blockdem
