// Face-integrated contact geometry: the overlap A∩B seen along the contact
// normal, split into cells over which the closure is linear, so that a joint law can be
// integrated exactly over the contact.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>

#include "blockdem/collision/small_vector.hpp"
#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// A convex cell of the contact plane with the closure at each vertex; the closure varies
/// linearly inside the cell. Up to 8 vertices are stored inline (no heap allocation).
struct ClosureCell {
  SmallVector<Eigen::Vector3d, 8> vertices;  ///< on the contact plane, in order (m)
  SmallVector<double, 8> closures;           ///< closure at each vertex, >= 0 (m)
};

struct FaceContactGeometry {
  /// True when at least one block presents a face to the contact plane (face-to-face,
  /// edge-to-face or vertex-to-face contact); false for edge-to-edge and similar contacts, which
  /// the caller treats as point contacts.
  bool face_type = false;
  /// Empty when !face_type or nothing overlaps; up to 8 cells are stored inline.
  SmallVector<ClosureCell, 8> cells;
};

struct FaceContactSettings {
  /// A block presents a face when the angle between one of its face normals and the contact
  /// normal is below this (rad).
  double face_angle = 0.2;
  /// Planes whose normal makes |n_j · n| below this with the contact normal bound the contact
  /// laterally instead of closing it (-).
  double lateral_tolerance = 1e-9;
};

/// A prestressed face: A's plane plane_a and B's plane plane_b coincide (opposite normals) where
/// the blocks share a face, and the joint there carries the closure e(x) = value + gradient ·
/// (x - point) (m), a field linear over the face, beyond the blocks' own overlap. The chord is
/// then that between the two face planes plus e; every other plane bounds the face laterally.
struct ClosureOffset {
  int plane_a = -1;                                    ///< index into planes_a
  int plane_b = -1;                                    ///< index into planes_b
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     ///< (m)
  double value = 0.0;                                  ///< e at point (m)
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  ///< (-)

  double at(const Eigen::Vector3d& x) const { return value + gradient.dot(x - point); }
};

/// Planes of either block that do not bound A∩B, to be left out of the chord: bit j of `a` (of
/// `b`) for plane j of A (of B) when the whole of the other block lies in that plane's half-space
/// (planes_holding). A∩B is then the same set with or without them, so the cells tile the same
/// projection; a plane left out still counts when telling whether its block presents a face.
struct RedundantPlanes {
  std::uint64_t a = 0;
  std::uint64_t b = 0;
};

/// The planes of `planes` (world frame; only the first 64) whose half-space holds the whole box
/// [box_min, box_max] (the other block's box: its vertices' bounds in the world frame) with
/// `clearance` (m) to spare, as a bit per plane: the box's farthest corner along each plane's
/// normal is at most the plane's offset less the clearance. The box holds the other block, so a
/// plane that holds the box holds the block. A plane flush with the other block (faces cut by one
/// joint, a column's sides) is kept: whether a plane is left out then changes only where the
/// blocks move by the clearance, not with round-off, which would make the cells, and the forces,
/// jump between two roundings of one geometry from step to step. A block of more than 64 planes
/// has none above the 64th left out.
std::uint64_t planes_holding(std::span<const Halfspace> planes, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, double clearance);

/// The chord of A∩B along n through a point y of the plane through `origin` normal to n is
/// g(y) = min over planes facing +n of (s_j/c_j) - max over planes facing -n of (s_j/c_j),
/// with c_j = n_j·n and s_j the slack of plane j at y. Each pair (upper plane, lower plane)
/// that is active somewhere gives one cell where g is linear; the cells tile the projection of
/// A∩B on the plane exactly. `extent` (m) must exceed the size of A∩B.
/// Cost: the planes in `redundant` are dropped first (each block's far faces); the projection of
/// A∩B is clipped once against every (upper, lower) pair; the region where each upper plane is the
/// lowest (and each lower plane the highest) is then clipped within it, and only pairs of non-empty
/// regions whose boxes meet form cells. Polygons live in a stack buffer while no polygon can see
/// more than 128 clips, and the planes in a stack table for up to 32 planes in all (heap buffers
/// beyond). With `offset`, a prestressed face (ClosureOffset): `origin` should lie on the face,
/// where the other planes' traces bound it. `redundant` planes (RedundantPlanes) are left out of
/// the chord and the cells; not with `offset`, where every plane but the two faces bounds the face
/// by its trace.
FaceContactGeometry face_contact_geometry(std::span<const Halfspace> planes_a,
                                          std::span<const Halfspace> planes_b,
                                          const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& normal, double extent,
                                          const FaceContactSettings& settings = {},
                                          const ClosureOffset* offset = nullptr,
                                          RedundantPlanes redundant = {});

}  // namespace blockdem
