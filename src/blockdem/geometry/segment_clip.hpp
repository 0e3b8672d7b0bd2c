// The part of a line segment inside a convex polyhedron: the segment clipped by each of the
// polyhedron's half-spaces in turn (Cyrus & Beck 1978, parametric line clipping).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <utility>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// The interval of parameters [t_in, t_out] ⊂ [0, 1] of the points p0 + t (p1 - p0) that lie in
/// every half-space of `planes` (a convex polyhedron), or nothing when that set is empty or a
/// single point. Exact in the sense of the half-spaces: each plane n·x <= d cuts the interval at
/// t = (d - n·p0) / (n·(p1 - p0)); a segment parallel to a plane is kept or dropped whole.
std::optional<std::pair<double, double>> clip_segment(std::span<const Halfspace> planes,
                                                      const Eigen::Vector3d& p0,
                                                      const Eigen::Vector3d& p1);

}  // namespace blockdem
