// Newton's method for the analytic centre (Boon et al. 2012, section 2.2; Boyd & Vandenberghe
// 2004, section 9.6 for the damped Newton method on self-concordant barriers).
#include "blockdem/collision/analytic_centre.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

namespace blockdem {

namespace {

// Gradient g = Σ n_j / s_j and Hessian H = Σ n_j n_jᵀ / s_j² of φ at x (slack s_j = d_j - n_j·x),
// H as its six upper entries. False if x is not strictly inside every plane.
struct Derivatives {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0;
  double inverse_slack_sum = 0;  // Σ 1/s_j (1/m), for the round-off floor of the decrement

  bool evaluate(const PlaneColumns& planes, const Eigen::Vector3d& x) {
    // Two planes at a time (SSE2 packets), even and odd planes summed separately.
    using Pair = Eigen::Array2d;
    const double* nx = planes.nx();
    const double* ny = planes.ny();
    const double* nz = planes.nz();
    const double* d = planes.d();
    const std::size_t m = planes.size();
    Pair gx = Pair::Zero(), gy = Pair::Zero(), gz = Pair::Zero();
    Pair hxx = Pair::Zero(), hxy = Pair::Zero(), hxz = Pair::Zero();
    Pair hyy = Pair::Zero(), hyz = Pair::Zero(), hzz = Pair::Zero();
    Pair inv_sum = Pair::Zero();
    Pair min_slack = Pair::Constant(std::numeric_limits<double>::infinity());
    std::size_t j = 0;
    auto accumulate = [&](const Pair& px, const Pair& py, const Pair& pz, const Pair& pd) {
      const Pair slack = pd - (px * x.x() + py * x.y() + pz * x.z());
      min_slack = min_slack.min(slack);
      const Pair inv = slack.inverse();
      inv_sum += inv;
      const Pair wx = px * inv, wy = py * inv, wz = pz * inv;
      gx += wx;
      gy += wy;
      gz += wz;
      hxx += wx * wx;
      hxy += wx * wy;
      hxz += wx * wz;
      hyy += wy * wy;
      hyz += wy * wz;
      hzz += wz * wz;
    };
    for (; j + 1 < m; j += 2) {
      accumulate(Pair::Map(nx + j), Pair::Map(ny + j), Pair::Map(nz + j), Pair::Map(d + j));
    }
    if (j < m) {
      // The last plane of an odd count, paired with a plane that adds nothing (n = 0, d = +∞:
      // its inverse slack is 0).
      accumulate(Pair(nx[j], 0.0), Pair(ny[j], 0.0), Pair(nz[j], 0.0),
                 Pair(d[j], std::numeric_limits<double>::infinity()));
    }
    g = Eigen::Vector3d(gx.sum(), gy.sum(), gz.sum());
    h00 = hxx.sum();
    h01 = hxy.sum();
    h02 = hxz.sum();
    h11 = hyy.sum();
    h12 = hyz.sum();
    h22 = hzz.sum();
    inverse_slack_sum = inv_sum.sum();
    return min_slack.minCoeff() > 0.0;
  }

  // The Newton step Δ = -H⁻¹ g by the square-root-free Cholesky factorisation H = L D Lᵀ
  // (L unit lower triangular; Golub & Van Loan, Matrix Computations, 4th ed., Alg. 4.1.2) on the
  // symmetric 3x3; returns λ² = gᵀ H⁻¹ g = Σ_k z_k² / D_k with L z = -g (NaN if H is not
  // positive definite). Three reciprocals and no square root: the chain of dependent divisions
  // and square roots of the LLᵀ form was half the time of an iteration.
  double newton_step(Eigen::Vector3d& step) const {
    const double inv0 = 1.0 / h00;
    const double l10 = h01 * inv0, l20 = h02 * inv0;
    const double d1 = h11 - l10 * h01;
    const double inv1 = 1.0 / d1;
    const double e21 = h12 - l20 * h01;  // D_1 L_21
    const double l21 = e21 * inv1;
    const double d2 = h22 - l20 * h02 - l21 * e21;
    if (!(h00 > 0.0 && d1 > 0.0 && d2 > 0.0)) {
      step.setConstant(std::numeric_limits<double>::quiet_NaN());
      return std::numeric_limits<double>::quiet_NaN();
    }
    const double inv2 = 1.0 / d2;
    const double z0 = -g.x();
    const double z1 = -g.y() - l10 * z0;
    const double z2 = -g.z() - l20 * z0 - l21 * z1;
    step.z() = z2 * inv2;
    step.y() = z1 * inv1 - l21 * step.z();
    step.x() = z0 * inv0 - l10 * step.y() - l20 * step.z();
    return z0 * z0 * inv0 + z1 * z1 * inv1 + z2 * z2 * inv2;
  }
};

}  // namespace

AnalyticCentreResult analytic_centre(std::span<const Halfspace> planes,
                                     const Eigen::Vector3d& start, int max_iterations) {
  return analytic_centre(PlaneColumns(planes), start, max_iterations);
}

AnalyticCentreResult analytic_centre(const PlaneColumns& planes, const Eigen::Vector3d& start,
                                     int max_iterations) {
  AnalyticCentreResult out;
  Eigen::Vector3d x = start;
  Derivatives d;
  // A full step tried in the damped phase: the point it left, its Newton step and damped length.
  bool trial = false;
  Eigen::Vector3d trial_from = x, trial_step = Eigen::Vector3d::Zero();
  double damped_length = 0.0;
  // Round-off floor of the decrement. A slack s_j = d_j - n_j·x is computed with an error below
  // e = 4 ε (max_j |d_j| + |x|) (three products and three sums, |n_j| = 1, and x itself moves in
  // steps of its last bit), which changes the gradient by δg = Σ n_j δs_j / s_j² and the
  // decrement by at most Σ_j e / s_j, since n_jᵀ H⁻¹ n_j / s_j² <= 1 (H ⪰ n_j n_jᵀ / s_j²).
  // Below that floor the measured decrement is noise: in the thin overlap of faces that touch
  // to a nanometre, 1 m from the origin, it is ~1e-6 and the 1e-6 test alone is never met.
  // The largest |d_j| is found when the floor is first needed (a warm start that converges at
  // once never needs it).
  double largest_offset = -1.0;
  constexpr double kSlackError = 4.0 * std::numeric_limits<double>::epsilon();
  int steps_at_floor = 0;  // consecutive full steps taken from λ at or below the floor
  for (int it = 0; it < max_iterations; ++it) {
    out.iterations = it + 1;
    const bool inside = d.evaluate(planes, x);
    if (trial) {
      // Keep the full step only if φ decreased all along it: x strictly inside and
      // ψ'(1) = g(x)·Δ <= 0 for ψ(t) = φ(x_old + tΔ), convex. Then φ(x) <= φ at the damped
      // point, so the damped method's guaranteed decrease still holds. Else take the damped step.
      trial = false;
      if (!inside || !(d.g.dot(trial_step) <= 0.0)) {
        x = trial_from + damped_length * trial_step;
        continue;
      }
    } else if (!inside) {
      break;  // only possible for a start outside (the caller's contract) or non-finite planes
    }
    if (it == 0) out.start_inside = true;
    Eigen::Vector3d step;
    const double lambda2 = d.newton_step(step);
    out.decrement = std::sqrt(lambda2);
    if (!std::isfinite(lambda2)) break;
    if (lambda2 < 1e-20) {
      x += step;
      out.converged = true;
      break;
    }
    const double lambda = std::sqrt(lambda2);
    if (lambda < 0.25) {
      // Quadratic phase: after a full step the decrement is at most (λ/(1-λ))² (B&V eq. 9.50
      // for self-concordant functions), so below 1e-12 as soon as λ/(1-λ) < 1e-6: the
      // round-off floor of the gradient (slacks of a 10 µm overlap of 46 mm blocks carry
      // relative errors ~1e-12), where one more evaluation could not improve the point. Or
      // after a second full step from λ at or below its round-off floor: the first left at most
      // (λ/(1-λ))² of the decrement that is not noise (the directions along the thin overlap,
      // measured in the Hessian norm), the second removes that too.
      if (lambda < 1e-6 * (1.0 - lambda)) {
        x += step;
        out.converged = true;
        break;
      }
      if (largest_offset < 0.0) {
        largest_offset = 0.0;
        for (std::size_t j = 0; j < planes.size(); ++j) {
          largest_offset = std::max(largest_offset, std::abs(planes.d()[j]));
        }
      }
      const double floor = kSlackError * (largest_offset + x.norm()) * d.inverse_slack_sum;
      steps_at_floor = lambda <= floor ? steps_at_floor + 1 : 0;
      x += step;
      if (steps_at_floor == 2) {
        out.converged = true;
        break;
      }
      continue;
    }
    // Damped phase: try the full step (checked at the next evaluation), which moves away from a
    // near wall twice as fast as the damped step 1/(1+λ) (Newton doubles the slack of a wall the
    // point sits close to).
    trial = true;
    trial_from = x;
    trial_step = step;
    damped_length = 1.0 / (1.0 + lambda);
    x += step;
  }
  // A full step still unchecked when the iterations ran out falls back to the damped one.
  if (trial) x = trial_from + damped_length * trial_step;
  out.point = x;
  return out;
}

}  // namespace blockdem
