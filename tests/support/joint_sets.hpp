// A persistent joint set for the rock-slicing tests.
#pragma once

#include <Eigen/Core>
#include <string>

#include "blockdem/rockmass/joint_set.hpp"

namespace blockdem::test {

/// A persistent set of dip and dip direction (degrees), constant spacing (m), through `origin`.
inline JointSet persistent_set(const std::string& name, double dip, double dir, double spacing,
                               const Eigen::Vector3d& origin) {
  JointSet s;
  s.name = name;
  s.dip_deg = dip;
  s.dip_direction_deg = dir;
  s.spacing.mean = spacing;
  s.origin = origin;
  return s;
}

}  // namespace blockdem::test
