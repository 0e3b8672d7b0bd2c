// Analytic centre of a set of half-spaces: the contact point of Boon et al. (2012).
#pragma once

#include <Eigen/Core>
#include <span>

#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

struct AnalyticCentreResult {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< the analytic centre (m)
  int iterations = 0;                               ///< Newton iterations taken
  bool converged = false;
};

/// Minimiser of φ(x) = -Σ_j ln(d_j - n_j·x) over the interior of {n_j·x <= d_j}, by damped Newton
/// (Nesterov & Nemirovskii's step 1/(1+λ) while the Newton decrement λ > 1/4, full steps after),
/// which keeps every iterate strictly feasible. `start` must be strictly inside every plane.
/// Converged when λ² < 1e-20 (λ is dimensionless, so the test is scale-free).
AnalyticCentreResult analytic_centre(std::span<const Halfspace> planes, const Eigen::Vector3d& start,
                                     int max_iterations = 60);

}  // namespace blockdem
