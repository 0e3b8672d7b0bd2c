// Two blocks that share a face: coincident, opposite planes whose faces overlap with positive area,
// as a rock mass's blocks do where one cut separated them. Finds the shared polygon's area and
// centroid, where a bonded joint between the blocks starts.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <span>
#include <vector>

#include "blockdem/geometry/halfspace.hpp"
#include "blockdem/geometry/polyhedron.hpp"

namespace blockdem {

/// The face that blocks A and B share.
struct SharedFace {
  int plane_a = -1;                                    ///< plane index of A's face
  int plane_b = -1;                                    ///< plane index of B's face
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   ///< A's outward normal, from A to B (-)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< centroid of the shared polygon (m)
  double area = 0.0;                                   ///< area of the shared polygon (m^2)
  std::vector<Eigen::Vector3d> polygon;                ///< its vertices, in order (m)
};

/// The largest face of A (shape `shape_a` at world vertices `vertices_a`, world planes `planes_a`)
/// that lies on a plane of B (`planes_b`) facing the other way, within `tolerance` (m) of it,
/// clipped by B's other planes: the polygon where A and B touch without overlapping. Empty when
/// no such polygon has an area above (tolerance)^2, nor above `min_area` (m^2): a caller that
/// takes no face below an area of its own says so here, and the polygons of blocks that meet
/// along an edge or at a corner (most neighbours of a rock mass's block) are dropped before
/// their moments are computed.
std::optional<SharedFace> shared_face(const Polyhedron& shape_a,
                                      std::span<const Eigen::Vector3d> vertices_a,
                                      std::span<const Halfspace> planes_a,
                                      std::span<const Halfspace> planes_b, double tolerance,
                                      double min_area = 0.0);
/// The same for A at a pose (its world vertices position + orientation · v, found only for the
/// faces that lie on one of B's planes).
std::optional<SharedFace> shared_face(const Polyhedron& shape_a,
                                      const Eigen::Quaterniond& orientation_a,
                                      const Eigen::Vector3d& position_a,
                                      std::span<const Halfspace> planes_a,
                                      std::span<const Halfspace> planes_b, double tolerance,
                                      double min_area = 0.0);

}  // namespace blockdem
