// A bracketing scalar root finder (Brent's method: inverse quadratic interpolation and secant
// steps, falling back to bisection), used by the continuously-yielding shear return mapping.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "blockdem/numerics/number_text.hpp"

namespace blockdem {

/// Finds x in [lo, hi] with f(x) = 0, given f_lo = f(lo) and f_hi = f(hi) of opposite signs (or
/// one of them zero). Stops when the bracket is narrower than about 2 (rel_tol |x| + abs_tol).
/// Brent, R. P. (1973) Algorithms for Minimization without Derivatives, ch. 4: every step keeps a
/// sign change, so the method converges at least as fast as bisection.
/// Throws std::invalid_argument if the bracket holds no sign change and std::runtime_error if
/// max_iterations are exhausted (impossible for a continuous f and max_iterations >= ~2100).
template <class Function>
double find_root_bracketed(Function&& f, double lo, double hi, double f_lo, double f_hi,
                           double rel_tol, double abs_tol, int max_iterations = 300) {
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if ((f_lo > 0.0) == (f_hi > 0.0) || std::isnan(f_lo) || std::isnan(f_hi)) {
    throw std::invalid_argument("find_root_bracketed: no sign change in the bracket, f(lo) = " +
                                number_text(f_lo) + ", f(hi) = " + number_text(f_hi));
  }
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // b: best estimate; a: previous b; c: the point that brackets the root with b.
  double a = lo, fa = f_lo, b = hi, fb = f_hi;
  double c = a, fc = fa;
  double step = b - a, previous_step = step;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    if ((fb > 0.0) == (fc > 0.0)) {
      // b and c no longer bracket: the last point a becomes the opposite end.
      c = a;
      fc = fa;
      step = previous_step = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      // Keep the smaller residual in b.
      a = b;
      fa = fb;
      b = c;
      fb = fc;
      c = a;
      fc = fa;
    }
    const double tol = 2.0 * eps * std::abs(b) + 0.5 * (rel_tol * std::abs(b) + abs_tol);
    const double half_width = 0.5 * (c - b);
    if (std::abs(half_width) <= tol || fb == 0.0) return b;

    if (std::abs(previous_step) >= tol && std::abs(fa) > std::abs(fb)) {
      // Interpolate: secant through (a, b) or inverse quadratic through (a, b, c).
      double p = 0.0, q = 0.0;
      const double s = fb / fa;
      if (a == c) {
        p = 2.0 * half_width * s;
        q = 1.0 - s;
      } else {
        const double qa = fa / fc;
        const double r = fb / fc;
        p = s * (2.0 * half_width * qa * (qa - r) - (b - a) * (r - 1.0));
        q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) {
        q = -q;
      } else {
        p = -p;
      }
      // Accept the interpolation only if it stays well inside the bracket and shrinks fast.
      if (2.0 * p <
          std::min(3.0 * half_width * q - std::abs(tol * q), std::abs(previous_step * q))) {
        previous_step = step;
        step = p / q;
      } else {
        step = previous_step = half_width;
      }
    } else {
      step = previous_step = half_width;
    }
    a = b;
    fa = fb;
    b += (std::abs(step) > tol) ? step : (half_width > 0.0 ? tol : -tol);
    fb = f(b);
  }
  throw std::runtime_error("find_root_bracketed: no convergence in " +
                           std::to_string(max_iterations) + " iterations");
}

}  // namespace blockdem
