// Narrow phase of Boon et al. (2012) as used by Boon et al. (2015): LP overlap test, analytic
// centre contact point, rounded inner-potential normal, chord overlap and slice area.
#pragma once

#include <span>

#include "blockdem/collision/contact_geometry.hpp"
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

/// Optional memory between time steps for a persistent contact (warm starts).
struct Boon2012Cache {
  bool valid = false;
  Eigen::Vector3d last_point = Eigen::Vector3d::Zero();
};

/// Contact geometry of blocks A and B given their planes in world coordinates. `extent` (m) must
/// exceed the size of A∩B (e.g. the sum of the blocks' bounding radii).
ContactGeometry boon2012_contact(std::span<const Halfspace> planes_a,
                                 std::span<const Halfspace> planes_b, double extent,
                                 const Boon2012Settings& settings, Boon2012Cache* cache = nullptr);

/// Rounded normal of one block at x (DESIGN section 2 step 3): the gradient of
/// f(x) = Σ_i <n_i·x - (d_i - r_round)>², i.e. 2 Σ_i <n_i·x - d_i + r_round> n_i; when x lies
/// deeper than r_round behind every face, the gradient the nearest face would give on its own
/// plane, 2 r_round n_nearest (the same scale as a gradient at the surface).
Eigen::Vector3d potential_gradient(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                                   double rounding_distance);

/// Length of the chord of {n_j·x <= d_j} through x along the unit direction u (m).
double chord_length(std::span<const Halfspace> planes, const Eigen::Vector3d& x,
                    const Eigen::Vector3d& u);

}  // namespace blockdem
