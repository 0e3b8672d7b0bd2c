// Damped Newton for the analytic centre (Boon et al. 2012, section 2.2; Boyd & Vandenberghe 2004,
// section 9.6 for the damped Newton method on self-concordant barriers).
#include "blockdem/collision/analytic_centre.hpp"

#include <cmath>

namespace blockdem {

AnalyticCentreResult analytic_centre(std::span<const Halfspace> planes, const Eigen::Vector3d& start,
                                     int max_iterations) {
  AnalyticCentreResult out;
  Eigen::Vector3d x = start;
  for (int it = 0; it < max_iterations; ++it) {
    // Gradient g = Σ n_j / s_j and Hessian H = Σ n_j n_jᵀ / s_j² of φ at x (slack s_j = d_j - n_j·x).
    double h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (const auto& p : planes) {
      const double inv = 1.0 / (p.offset - p.normal.dot(x));
      const Eigen::Vector3d w = p.normal * inv;
      g += w;
      h00 += w.x() * w.x();
      h01 += w.x() * w.y();
      h02 += w.x() * w.z();
      h11 += w.y() * w.y();
      h12 += w.y() * w.z();
      h22 += w.z() * w.z();
    }
    // Solve H Δ = -g by Cholesky on the symmetric 3x3.
    const double l00 = std::sqrt(h00);
    const double l10 = h01 / l00, l20 = h02 / l00;
    const double l11 = std::sqrt(h11 - l10 * l10);
    const double l21 = (h12 - l20 * l10) / l11;
    const double l22 = std::sqrt(h22 - l20 * l20 - l21 * l21);
    const double y0 = -g.x() / l00;
    const double y1 = (-g.y() - l10 * y0) / l11;
    const double y2 = (-g.z() - l20 * y0 - l21 * y1) / l22;
    Eigen::Vector3d step;
    step.z() = y2 / l22;
    step.y() = (y1 - l21 * step.z()) / l11;
    step.x() = (y0 - l10 * step.y() - l20 * step.z()) / l00;
    // Newton decrement λ² = gᵀ H⁻¹ g = |y|².
    const double lambda2 = y0 * y0 + y1 * y1 + y2 * y2;
    out.iterations = it + 1;
    if (!std::isfinite(lambda2)) break;
    if (lambda2 < 1e-20) {
      x += step;
      out.converged = true;
      break;
    }
    const double lambda = std::sqrt(lambda2);
    x += (lambda > 0.25 ? 1.0 / (1.0 + lambda) : 1.0) * step;
  }
  out.point = x;
  return out;
}

}  // namespace blockdem
