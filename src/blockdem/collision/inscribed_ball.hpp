// The overlap test of Boon et al. (2012): the largest ball inside an intersection of half-spaces,
// found by a 4-variable linear program solved with a small dense active-set method.
#pragma once

#include <array>
#include <span>

#include <Eigen/Core>

#include "blockdem/collision/plane_columns.hpp"
#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

/// Solution of   maximise r  subject to  n_j · x + r <= d_j  for every plane j   (x in R^3, r).
///
/// With unit normals, `radius` is r*, the radius of the largest ball inside the intersection of the
/// half-spaces, and `center` is a centre x* of such a ball. For the planes of two convex blocks,
/// the blocks overlap iff r* > 0; r* = 0 when they touch and r* < 0 when they are apart (then -r*
/// is the largest common amount by which every plane can be pushed outward before the
/// intersection becomes non-empty). x* need not be unique (e.g. two boxes in face contact have a
/// whole region of optimal centres); r* is.
struct InscribedBall {
  double radius = 0.0;                               ///< r*; +infinity when unbounded (m)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< x*, a centre of the largest ball (m)
  /// False when r is unbounded: the normals do not positively span R^3, i.e. the half-spaces
  /// contain arbitrarily large balls. Never happens for the planes of a bounded block.
  bool bounded = true;
  int iterations = 0;  ///< active-set steps (primal steps, drops and dual pivots) taken (-)
  /// Indices (into the plane list) of the planes tight at x* that define the solution, for a warm
  /// start; the first `num_active` entries are valid. A vertex solution has 4.
  std::array<int, 4> active = {-1, -1, -1, -1};
  int num_active = 0;  ///< number of valid entries in `active` (0..4) (-)
  /// True if a warm start was given up and the primal method restarted from a single plane at
  /// the previous centre or the dual simplex's last vertex (a diagnostic of the warm path; a cold
  /// solve leaves it false).
  bool restarted = false;
};

/// Cold solve. `planes` holds unit outward normals (the caller's contract: normalised, finite).
/// Starts from the mean of the planes' foot points d_j n_j and walks up the active-set path.
/// No heap allocation for up to `kInscribedBallStackPlanes` planes; longer lists use a heap
/// buffer. Throws std::invalid_argument for an empty list or a non-finite plane, and
/// std::runtime_error if the iteration limit is hit (a numerical failure, never expected).
InscribedBall largest_inscribed_ball(std::span<const Halfspace> planes);

/// Warm start from the solution of the same pair at the previous time step. The plane list must
/// have the same order as then (e.g. the planes of A, then those of B); the planes may have moved.
/// If `previous` has a full active set (4 planes) that is still dual feasible (non-negative
/// multipliers) with the new planes, a dual simplex repairs primal feasibility, usually in 0-2
/// pivots. A smaller active set (a non-vertex optimum, e.g. face-to-face contact), or a vertex
/// whose multipliers are no longer all non-negative, is re-entered at the nearest point where its
/// planes (failing that, a vertex's planes with positive multipliers) are tight, if that point is
/// feasible. Otherwise the primal active-set method restarts from `previous.center` (`restarted`).
/// Any `previous` is safe (an unrelated one only costs time). The optimum radius is the same as a
/// cold solve gives (to round-off, within 1e-13 of the planes' extent); the centre may differ where
/// it is not unique. As a check of that, a warm result whose radius is below the previous centre's
/// (a feasible point's radius, so a lower bound of the optimum) by more than 1e-10 of the planes'
/// offsets is replaced by the cold solve (`restarted`).
InscribedBall largest_inscribed_ball(std::span<const Halfspace> planes,
                                     const InscribedBall& previous);

/// The same two solves for planes stored column by column (the narrow phase's layout): the same
/// bits as for the planes in a list.
InscribedBall largest_inscribed_ball(const PlaneColumns& planes);
InscribedBall largest_inscribed_ball(const PlaneColumns& planes, const InscribedBall& previous);

/// Plane lists up to this length are solved without heap allocation.
inline constexpr int kInscribedBallStackPlanes = 64;

}  // namespace blockdem
