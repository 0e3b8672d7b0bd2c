// What the narrow phase reports for a touching pair: point, normal, overlap, area.
#pragma once

#include <Eigen/Core>

#include "blockdem/collision/slice_polygon.hpp"

namespace blockdem {

/// Contact geometry of blocks A and B. The normal points from A to B.
struct ContactGeometry {
  bool touching = false;                              ///< the LP found r* > tolerance
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< contact point x_c (m)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal, from A to B (-)
  double overlap = 0.0;           ///< δ: chord of A∩B through x_c along n (m)
  double area = 0.0;              ///< A_c: area of the slice of A∩B at x_c (m^2)
  double inscribed_radius = 0.0;  ///< r* of the overlap LP (m)
  Eigen::Vector3d inscribed_centre = Eigen::Vector3d::Zero();  ///< x* of the overlap LP (m)
  SlicePolygon slice;  ///< the slice polygon whose area is A_c
};

}  // namespace blockdem
