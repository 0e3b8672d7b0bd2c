// Line-of-thrust fits of a voussoir beam: a parabola by linear least squares
// and a uniform catenary by Levenberg-Marquardt, each with the horizontal thrust its curvature
// implies for a given distributed load. Pure maths: points in, curves and thrusts out.
#pragma once

#include <Eigen/Core>

#include "blockdem/numerics/least_squares.hpp"

namespace blockdem {

/// Parabola y = c0 + c1 x + c2 x^2 fitted to thrust points by least squares on vertical residuals.
struct ParabolaFit {
  double c0 = 0.0;            ///< constant term (m)
  double c1 = 0.0;            ///< slope term (-)
  double c2 = 0.0;            ///< curvature term, y'' = 2 c2 (1/m)
  double rms_residual = 0.0;  ///< RMS of y_fit(x_i) - y_i (m)
  /// False when the points are collinear to within 1e-9 of the data's size: the sagitta
  /// |c2| (dx/2)^2 over the x range dx is then rounding noise and c2 carries no information.
  bool curvature_resolved = false;

  double evaluate(double x) const { return c0 + (c1 + c2 * x) * x; }  ///< y (m) at x (m)
  /// Abscissa of the vertex, -c1 / (2 c2) (m). Throws std::domain_error if the curvature is not
  /// resolved.
  double vertex_x() const;
};

/// Fits y = c0 + c1 x + c2 x^2 to the points (x_i, y_i) (m) by column-pivoted QR on the
/// Vandermonde matrix of the centred, scaled abscissa t = (x - mean x) / (half range), then maps
/// the coefficients back to x. Throws std::invalid_argument if x and y differ in size, there are
/// fewer than 3 points or fewer than 3 distinct x values, or an entry is not finite.
ParabolaFit fit_parabola(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

/// Horizontal thrust implied by the parabola for a load w uniformly distributed per unit
/// horizontal length (span). A funicular under such a load obeys H y'' = -w, so
/// H = w / |y''| = w / (2 |c2|). For a beam of weight W on span S, w = W / S and, with the sag z
/// between abutment and midspan thrust points, H = W S / (8 z).
/// Units follow w: w in N/m gives H in N; w in N/m per metre of width gives N/m.
/// Throws std::invalid_argument if w is not positive and finite, std::domain_error if the
/// curvature is not resolved (collinear points: H -> infinity).
double parabola_implied_thrust(const ParabolaFit& fit, double load_per_unit_span);

/// Uniform catenary y = y0 - a [cosh((x - x0) / a) - 1]. a > 0 is an arch (concave down, apex at
/// x0, the shape of a voussoir beam's line of thrust); a < 0 is a hanging chain.
struct CatenaryFit {
  double y0 = 0.0;            ///< ordinate of the vertex (m)
  double x0 = 0.0;            ///< abscissa of the vertex (m)
  double a = 0.0;             ///< catenary parameter H / q, radius of curvature at the vertex (m)
  double rms_residual = 0.0;  ///< RMS of y_fit(x_i) - y_i (m)
  int iterations = 0;         ///< Levenberg-Marquardt steps used (0 for a guess) (-)

  double evaluate(double x) const;  ///< y (m) at x (m)
};

/// The starting point of the catenary fit from a parabola: vertex x0 = -c1 / (2 c2),
/// a = -1 / (2 c2) (equal curvature at the vertex), y0 = parabola value at x0.
/// Throws std::domain_error if the parabola's curvature is not resolved.
CatenaryFit catenary_guess_from_parabola(const ParabolaFit& parabola);

/// Fits the uniform catenary to the points (m) by Levenberg-Marquardt on vertical residuals with
/// the analytic Jacobian, started from the least-squares parabola's guess. Throws
/// std::invalid_argument for the same bad input as fit_parabola, std::domain_error if the points
/// are collinear (a -> infinity: no finite catenary), std::runtime_error if Levenberg-Marquardt
/// does not converge.
CatenaryFit fit_catenary(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                         const LevenbergMarquardtOptions& options = {});

/// As above, from a caller's initial guess (its y0, x0, a; a must be non-zero and finite).
CatenaryFit fit_catenary(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                         const CatenaryFit& initial_guess,
                         const LevenbergMarquardtOptions& options = {});

/// Horizontal thrust implied by the catenary, H = q |a|, for a load q per unit ARC LENGTH of the
/// curve (the hanging chain's own weight). A voussoir beam's weight is uniform per unit span,
/// not per unit arc length of its thrust line; using q = W / S is exact to first order: the arc
/// length element is ds = sqrt(1 + y'^2) dx, so the two loadings differ by a factor
/// 1 + y'^2 / 2 + O(y'^4), below 0.1 % for slopes |y'| < 0.045. Units follow q as for the parabola.
/// Throws std::invalid_argument if q is not positive and finite or a is zero or not finite.
double catenary_implied_thrust(const CatenaryFit& fit, double load_per_unit_arc_length);

/// Both fits of one set of thrust points and the thrusts they imply.
struct ThrustLineFit {
  ParabolaFit parabola;
  CatenaryFit catenary;
  double load_per_unit_span = 0.0;  ///< w = W / S used for both thrusts (N/m, or N/m^2 per width)
  double parabola_thrust = 0.0;     ///< H = w / (2 |c2|) (N, or N/m per width)
  double catenary_thrust = 0.0;     ///< H = w |a|, q taken as w (N, or N/m per width)
};

/// Fits the parabola and the catenary to the thrust points and evaluates both implied thrusts
/// with the beam's weight per unit span, load_per_unit_span = W / S, as the load of each curve
/// (see the two thrust functions for what that assumes). Throws as the functions it calls.
ThrustLineFit fit_thrust_line(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                              double load_per_unit_span,
                              const LevenbergMarquardtOptions& options = {});

}  // namespace blockdem
