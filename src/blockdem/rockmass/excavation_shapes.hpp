// Excavation outlines as convex plane sets: tunnels (circle or horseshoe along an axis of given
// trend and plunge), boxes, and slope cuts (half-spaces).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

struct TunnelSpec {
  enum class Profile { circle, horseshoe };
  Profile profile = Profile::horseshoe;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< centre of the circle / roof arch (m)
  double radius = 1.0;                               ///< (m)
  double wall_height = 1.0;      ///< horseshoe: floor this far below the centre (m)
  double trend_deg = 0.0;        ///< axis direction, clockwise from north (degrees)
  double plunge_deg = 0.0;       ///< axis dip below horizontal, in [-90, 90] (degrees)
  int sides = 16;                ///< polygon sides of the circle (arch: half of them)
  std::optional<double> length;  ///< (m); absent: through the whole region

  /// Unit axis a = (cos p sin t, cos p cos t, -sin p) (-).
  Eigen::Vector3d axis() const;
};

/// The tunnel's interior as planes {n·x <= d}: the circle as the regular polygon inscribed in
/// it; the horseshoe as an arch inscribed in the upper half circle on vertical walls x = ±r (in
/// the section's horizontal axis) and a flat floor `wall_height` below the centre.
std::vector<Halfspace> tunnel_planes(const TunnelSpec& t);

}  // namespace blockdem
