// Parabola and uniform-catenary fits of a line of thrust and the thrusts they imply (see header).
#include "blockdem/analysis/thrust_line_fit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace blockdem {
namespace {

// Relative size below which a parabola's sagitta is treated as rounding noise.
constexpr double kCollinearTolerance = 1e-9;

void check_points(const Eigen::VectorXd& x, const Eigen::VectorXd& y, const char* who) {
  if (x.size() != y.size()) {
    std::ostringstream msg;
    msg << who << ": x has " << x.size() << " values but y has " << y.size();
    throw std::invalid_argument(msg.str());
  }
  if (x.size() < 3) {
    std::ostringstream msg;
    msg << who << ": need at least 3 thrust points for a 3-parameter curve, got " << x.size();
    throw std::invalid_argument(msg.str());
  }
  if (!x.allFinite() || !y.allFinite()) {
    throw std::invalid_argument(std::string(who) + ": thrust points contain NaN or Inf");
  }
}

// 2 sinh^2(u/2) = cosh(u) - 1 without cancellation for small u.
double cosh_minus_one(double u) {
  const double s = std::sinh(0.5 * u);
  return 2.0 * s * s;
}

}  // namespace

double ParabolaFit::vertex_x() const {
  if (!curvature_resolved) {
    throw std::domain_error("parabola fit: curvature not resolved (collinear points), no vertex");
  }
  return -c1 / (2.0 * c2);
}

ParabolaFit fit_parabola(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  check_points(x, y, "parabola fit");
  // Centre and scale the abscissa so the Vandermonde columns are O(1): t in [-1, 1].
  const double x_min = x.minCoeff();
  const double x_max = x.maxCoeff();
  const double mid = 0.5 * (x_min + x_max);
  const double half_range = 0.5 * (x_max - x_min);
  if (!(half_range > 0.0)) {
    throw std::invalid_argument("parabola fit: all thrust points share one x value");
  }
  const Eigen::VectorXd t = (x.array() - mid) / half_range;
  Eigen::MatrixXd vandermonde(x.size(), 3);
  vandermonde.col(0).setOnes();
  vandermonde.col(1) = t;
  vandermonde.col(2) = t.array().square();

  LinearLeastSquaresSolution solution;
  try {
    solution = solve_linear_least_squares(vandermonde, y);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("parabola fit: need at least 3 distinct x values (") +
                                e.what() + ")");
  }
  const double d0 = solution.parameters(0);
  const double d1 = solution.parameters(1);
  const double d2 = solution.parameters(2);

  // Back to x: y = d0 + d1 (x - m)/h + d2 (x - m)^2/h^2.
  ParabolaFit fit;
  fit.c2 = d2 / (half_range * half_range);
  fit.c1 = d1 / half_range - 2.0 * d2 * mid / (half_range * half_range);
  fit.c0 = d0 - d1 * mid / half_range + d2 * mid * mid / (half_range * half_range);
  fit.rms_residual = solution.rms_residual;
  // The sagitta over the x range is |d2|; compare it with the size of the data.
  const double data_scale = std::max(2.0 * half_range, y.cwiseAbs().maxCoeff());
  fit.curvature_resolved = std::abs(d2) > kCollinearTolerance * data_scale;
  return fit;
}

double parabola_implied_thrust(const ParabolaFit& fit, double load_per_unit_span) {
  if (!(load_per_unit_span > 0.0 && std::isfinite(load_per_unit_span))) {
    throw std::invalid_argument("parabola thrust: load_per_unit_span must be positive and finite");
  }
  if (!fit.curvature_resolved) {
    throw std::domain_error(
        "parabola thrust: curvature not resolved (collinear thrust points), thrust unbounded");
  }
  // H y'' = -w with y'' = 2 c2.
  return load_per_unit_span / (2.0 * std::abs(fit.c2));
}

double CatenaryFit::evaluate(double x) const {
  return y0 - a * cosh_minus_one((x - x0) / a);
}

CatenaryFit catenary_guess_from_parabola(const ParabolaFit& parabola) {
  if (!parabola.curvature_resolved) {
    throw std::domain_error(
        "catenary fit: thrust points are collinear, the catenary parameter a -> infinity");
  }
  CatenaryFit guess;
  guess.x0 = parabola.vertex_x();
  guess.a = -1.0 / (2.0 * parabola.c2);
  guess.y0 = parabola.evaluate(guess.x0);
  guess.rms_residual = parabola.rms_residual;
  guess.iterations = 0;
  return guess;
}

CatenaryFit fit_catenary(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                         const LevenbergMarquardtOptions& options) {
  return fit_catenary(x, y, catenary_guess_from_parabola(fit_parabola(x, y)), options);
}

CatenaryFit fit_catenary(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                         const CatenaryFit& initial_guess,
                         const LevenbergMarquardtOptions& options) {
  check_points(x, y, "catenary fit");
  if (!(std::isfinite(initial_guess.a) && initial_guess.a != 0.0 &&
        std::isfinite(initial_guess.x0) && std::isfinite(initial_guess.y0))) {
    throw std::invalid_argument("catenary fit: initial guess needs finite y0, x0 and a != 0");
  }

  // Parameters p = (y0, x0, a); residual r_i = y0 - a [cosh(u_i) - 1] - y_i, u_i = (x_i - x0)/a.
  LeastSquaresModel model;
  model.residuals = [&x, &y](const Eigen::VectorXd& p) {
    Eigen::VectorXd r(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      r(i) = p(0) - p(2) * cosh_minus_one((x(i) - p(1)) / p(2)) - y(i);
    }
    return r;
  };
  // dr/dy0 = 1, dr/dx0 = sinh(u), dr/da = -[cosh(u) - 1] + u sinh(u).
  model.jacobian = [&x](const Eigen::VectorXd& p) {
    Eigen::MatrixXd jac(x.size(), 3);
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double u = (x(i) - p(1)) / p(2);
      jac(i, 0) = 1.0;
      jac(i, 1) = std::sinh(u);
      jac(i, 2) = -cosh_minus_one(u) + u * std::sinh(u);
    }
    return jac;
  };

  const Eigen::Vector3d start(initial_guess.y0, initial_guess.x0, initial_guess.a);
  const LevenbergMarquardtResult lm = levenberg_marquardt(model, start, options);
  if (!lm.converged() || !lm.parameters.allFinite() || lm.parameters(2) == 0.0) {
    std::ostringstream msg;
    msg << "catenary fit: Levenberg-Marquardt did not converge (" << to_string(lm.termination)
        << " after " << lm.iterations << " steps, a = " << lm.parameters(2)
        << " m); the points may be too close to a straight line";
    throw std::runtime_error(msg.str());
  }

  CatenaryFit fit;
  fit.y0 = lm.parameters(0);
  fit.x0 = lm.parameters(1);
  fit.a = lm.parameters(2);
  fit.rms_residual = lm.rms_residual;
  fit.iterations = lm.iterations;
  return fit;
}

double catenary_implied_thrust(const CatenaryFit& fit, double load_per_unit_arc_length) {
  if (!(load_per_unit_arc_length > 0.0 && std::isfinite(load_per_unit_arc_length))) {
    throw std::invalid_argument(
        "catenary thrust: load_per_unit_arc_length must be positive and finite");
  }
  if (!(std::isfinite(fit.a) && fit.a != 0.0)) {
    throw std::invalid_argument(
        "catenary thrust: catenary parameter a must be finite and non-zero");
  }
  // A chain of weight q per arc length has H = q a (the catenary of Lamb 1916, cited by the paper).
  return load_per_unit_arc_length * std::abs(fit.a);
}

ThrustLineFit fit_thrust_line(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                              double load_per_unit_span, const LevenbergMarquardtOptions& options) {
  ThrustLineFit result;
  result.parabola = fit_parabola(x, y);
  result.catenary = fit_catenary(x, y, catenary_guess_from_parabola(result.parabola), options);
  result.load_per_unit_span = load_per_unit_span;
  result.parabola_thrust = parabola_implied_thrust(result.parabola, load_per_unit_span);
  result.catenary_thrust = catenary_implied_thrust(result.catenary, load_per_unit_span);
  return result;
}

}  // namespace blockdem
