// Narrow phase of Boon et al. (2012) as used by Boon et al. (2015): LP overlap test, analytic
// centre contact point, rounded inner-potential normal, chord overlap and slice area.
#pragma once

#include <span>

#include "blockdem/collision/contact_geometry.hpp"
#include "blockdem/collision/inscribed_ball.hpp"
#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

struct Boon2012Settings {
  /// r_round: faces of the inner "potential particle" sit this far inside the block's faces (m).
  /// The paper's code used 0.2 mm on 46 mm blocks.
  double rounding_distance = 2e-4;
  /// Pairs whose inscribed radius r* is at most this are not in contact (m). Zero by default:
  /// a contact exists as soon as the blocks share interior points.
  double overlap_tolerance = 0.0;
};

/// Memory of one pair between time steps (warm starts). Results do not depend on it beyond
/// round-off: the overlap LP has a unique optimum radius, the analytic centre is unique and a
/// warm-started slice is verified to be the exact slice. The cache belongs to the plane lists of
/// A and B in a fixed order; a call with other plane counts clears it.
struct Boon2012Cache {
  int planes_a = -1;  ///< plane counts of A and B the cache was filled for (-1: empty)
  int planes_b = -1;
  /// The overlap LP's solution at the last call, for the planes of A followed by those of B.
  InscribedBall ball;
  bool has_ball = false;
  /// The contact point x_c of the last call that found a contact, where the analytic centre
  /// starts if it is still strictly inside A∩B (m).
  Eigen::Vector3d last_point = Eigen::Vector3d::Zero();
  bool has_point = false;
  SliceWarmStart slice;  ///< the planes of the last slice polygon's edges
};

/// Contact geometry of blocks A and B given their planes in world coordinates. `extent` (m) must
/// exceed the size of A∩B (e.g. the sum of the blocks' bounding radii). With a cache, the overlap
/// LP is warm-started from the cached solution and the cache is updated.
ContactGeometry boon2012_contact(std::span<const Halfspace> planes_a,
                                 std::span<const Halfspace> planes_b, double extent,
                                 const Boon2012Settings& settings, Boon2012Cache* cache = nullptr);

/// Steps 2-5 of the narrow phase for a pair whose overlap LP (step 1) has been solved already:
/// `ball` is the LP's solution for the planes of A followed by those of B, by any solver (the
/// benchmarks and tests pass a CLP solution here). Reads and updates the cache's contact point,
/// not its ball.
ContactGeometry boon2012_contact_from_ball(std::span<const Halfspace> planes_a,
                                           std::span<const Halfspace> planes_b,
                                           const InscribedBall& ball, double extent,
                                           const Boon2012Settings& settings,
                                           Boon2012Cache* cache = nullptr);

/// Steps 3 and 4 of the narrow phase at a contact point x_c found before: the normal and the
/// overlap, the same bits as boon2012_contact gives with that point.
void boon2012_normal_and_overlap(std::span<const Halfspace> planes_a,
                                 std::span<const Halfspace> planes_b, const Eigen::Vector3d& point,
                                 const Boon2012Settings& settings, Eigen::Vector3d& normal,
                                 double& overlap);

/// Rounded normal of one block at x: the gradient of
/// f(x) = Σ_i <n_i·x - (d_i - r_round)>², i.e. 2 Σ_i <n_i·x - d_i + r_round> n_i; when x lies
/// deeper than r_round behind every face, the gradient the nearest face would give on its own
/// plane, 2 r_round n_nearest (the same scale as a gradient at the surface).
Eigen::Vector3d potential_gradient(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                                   double rounding_distance);

/// Length of the chord of {n_j·x <= d_j} through x along the unit direction u (m).
double chord_length(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                    const Eigen::Vector3d& u);

}  // namespace blockdem
