// Analytic centre of a set of half-spaces: the contact point of Boon et al. (2012).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <span>

#include "blockdem/collision/plane_columns.hpp"
#include "blockdem/geometry/halfspace.hpp"

namespace blockdem {

struct AnalyticCentreResult {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< the analytic centre (m)
  int iterations = 0;                               ///< gradient and Hessian evaluations
  bool converged = false;
  bool start_inside = false;  ///< the start was strictly inside every plane (else nothing done)
  /// The Newton decrement λ measured at the last evaluation (-); NaN if none was made.
  double decrement = std::numeric_limits<double>::quiet_NaN();
};

/// Minimiser of φ(x) = -Σ_j ln(d_j - n_j·x) over the interior of {n_j·x <= d_j}, by Newton's
/// method. While the Newton decrement λ >= 1/4 a full step is tried and kept if φ decreases all
/// along it, else the damped step 1/(1+λ) of Nesterov & Nemirovskii is taken (a deviation from
/// the pure damped method that at least matches its decrease and leaves near walls twice as
/// fast); below 1/4, full steps. Every iterate is strictly feasible. `start` must be strictly
/// inside every plane (else the result is `start`, not converged, `start_inside` false).
/// Converged when the decrement at the returned point is at round-off level: a last full step
/// was taken from a point with λ < 1e-10 (measured), or from λ < 1e-6, after which it is at most
/// (λ/(1-λ))² < 1e-12 (λ is dimensionless: the test is scale-free), or after two consecutive
/// full steps from λ at or below its round-off floor Σ_j 4 ε (max_k |d_k| + |x|) / s_j (the
/// largest change of λ that the rounding of the slacks s_j can cause: nanometre-thin overlaps
/// far from the origin never reach 1e-6).
AnalyticCentreResult analytic_centre(std::span<const Halfspace> planes,
                                     const Eigen::Vector3d& start, int max_iterations = 60);

/// The same for planes stored column by column (the narrow phase's layout).
AnalyticCentreResult analytic_centre(const PlaneColumns& planes, const Eigen::Vector3d& start,
                                     int max_iterations = 60);

}  // namespace blockdem
