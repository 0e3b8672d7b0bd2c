// Normal-law calibration from a column compression test (see the header for the method).
#include "blockdem/calibration/normal_calibration.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

#include "blockdem/contact/law_params.hpp"
#include "blockdem/numerics/least_squares.hpp"

namespace blockdem {
namespace {

// The smallest curvature b u_max the exponential fit accepts: below it the law is linear to
// within 0.05 % over the data and a, b are not separately determined.
constexpr double kMinimumCurvature = 1e-3;
// The largest b u_max the starting scan tries (exp(200) ~ 7e86: no joint stiffens more).
constexpr double kMaximumCurvature = 200.0;

// Closure of the exponential law at stress sigma (m): the inverse of sigma = a [exp(b u) - 1].
double exponential_closure(double a, double b, double sigma) {
  return std::log1p(sigma / a) / b;
}

// Sum of squared relative closure residuals of the exponential law (a, b) (-).
double closure_cost(double a, double b, const std::vector<double>& stress,
                    const std::vector<double>& closure, const std::vector<double>& weight) {
  double cost = 0.0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    const double r = weight[i] * (exponential_closure(a, b, stress[i]) - closure[i]);
    cost += r * r;
  }
  return cost;
}

// Starting point: for b on a logarithmic grid of b u_max in [kMinimumCurvature,
// kMaximumCurvature], a minimising the stress misfit sum (a e_i - sigma_i)^2 with
// e_i = exp(b u_i) - 1 is sum(sigma e) / sum(e^2); keep the (a, b) of least closure cost.
Eigen::Vector2d starting_point(const std::vector<double>& stress,
                               const std::vector<double>& closure,
                               const std::vector<double>& weight, double max_closure,
                               const std::string& source) {
  constexpr int kGrid = 400;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best(0.0, 0.0);
  int best_index = -1;
  for (int g = 0; g <= kGrid; ++g) {
    const double t = static_cast<double>(g) / kGrid;
    const double b = std::exp(std::log(kMinimumCurvature) +
                              t * (std::log(kMaximumCurvature) - std::log(kMinimumCurvature))) /
                     max_closure;
    double se = 0.0;
    double ee = 0.0;
    for (std::size_t i = 0; i < stress.size(); ++i) {
      const double e = std::expm1(b * closure[i]);
      se += stress[i] * e;
      ee += e * e;
    }
    const double a = se / ee;
    if (!(a > 0.0 && std::isfinite(a))) continue;
    const double cost = closure_cost(a, b, stress, closure, weight);
    if (cost < best_cost) {
      best_cost = cost;
      best = Eigen::Vector2d(std::log(a), std::log(b));
      best_index = g;
    }
  }
  if (best_index < 0) {
    throw CalibrationError(source + ": no exponential law sigma = a [exp(b u) - 1] fits the data");
  }
  if (best_index == 0) {
    throw CalibrationError(source +
                           ": the joint closure shows no stiffening (the best exponential law "
                           "has b u_max <= 1e-3); the data call for the linear law");
  }
  return best;
}

}  // namespace

void ColumnTestDef::validate() const {
  if (!(modulus > 0.0 && std::isfinite(modulus))) {
    throw CalibrationError("modulus (E of the intact blocks) must be positive and finite, got " +
                           format_value(modulus) + " Pa");
  }
  if (!(height > 0.0 && std::isfinite(height))) {
    throw CalibrationError(
        "height (H of the column's intact blocks) must be positive and finite, "
        "got " +
        format_value(height) + " m");
  }
  if (joints < 1) {
    throw CalibrationError("joints (number of equivalent joints) must be at least 1, got " +
                           std::to_string(joints));
  }
}

NormalCalibration calibrate_normal(const ColumnCompressionData& data, const ColumnTestDef& test) {
  test.validate();
  if (data.stress.size() != data.displacement.size() || data.stress.size() != data.lines.size()) {
    throw std::invalid_argument("calibrate_normal: data vectors differ in size");
  }
  if (data.stress.size() < kMinimumColumnRows) {
    throw CalibrationError(data.source + ": " + std::to_string(data.stress.size()) +
                           " data rows; a column test needs at least " +
                           std::to_string(kMinimumColumnRows));
  }
  NormalCalibration cal;
  cal.test = test;
  cal.stress = data.stress;
  cal.displacement = data.displacement;
  // 1. Joint closure: intact deformation removed, shared by the equivalent joints.
  double max_closure = 0.0;
  for (std::size_t i = 0; i < data.stress.size(); ++i) {
    const double intact = data.stress[i] * test.height / test.modulus;
    const double u = (data.displacement[i] - intact) / test.joints;
    if (u < 0.0) {
      throw CalibrationError(
          data.source + ":" + std::to_string(data.lines[i]) +
          ": joint closure (d - sigma H / E) / N = " + format_value(u) +
          " m is negative: the intact deformation sigma H / E = " + format_value(intact) +
          " m exceeds the measured displacement d = " + format_value(data.displacement[i]) +
          " m; check the modulus (E = " + format_value(test.modulus) +
          " Pa) and the height (H = " + format_value(test.height) + " m)");
    }
    cal.intact_displacement.push_back(intact);
    cal.closure.push_back(u);
    max_closure = std::max(max_closure, u);
  }
  if (!(max_closure > 0.0)) {
    throw CalibrationError(data.source + ": no row has a positive joint closure; nothing to fit");
  }

  // 2. Exponential law, relative residuals in closure, parameters (ln a, ln b).
  const std::vector<double>& stress = cal.stress;
  const std::vector<double>& closure = cal.closure;
  const std::vector<double> weight = relative_weights(closure);
  const auto m = static_cast<Eigen::Index>(stress.size());
  LeastSquaresModel model;
  model.residuals = [&](const Eigen::VectorXd& p) {
    const double a = std::exp(p(0));
    const double b = std::exp(p(1));
    Eigen::VectorXd r(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto k = static_cast<std::size_t>(i);
      r(i) = weight[k] * (exponential_closure(a, b, stress[k]) - closure[k]);
    }
    return r;
  };
  model.jacobian = [&](const Eigen::VectorXd& p) {
    const double a = std::exp(p(0));
    const double b = std::exp(p(1));
    Eigen::MatrixXd jac(m, 2);
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double s = stress[k];
      // d/d(ln a) of ln(1 + s/a)/b = -(s / (a + s)) / b; d/d(ln b) = -ln(1 + s/a) / b.
      jac(i, 0) = -weight[k] * (s / (a + s)) / b;
      jac(i, 1) = -weight[k] * exponential_closure(a, b, s);
    }
    return jac;
  };
  const Eigen::Vector2d start = starting_point(stress, closure, weight, max_closure, data.source);
  const LevenbergMarquardtResult fit = levenberg_marquardt(model, start);
  if (!fit.converged()) {
    throw CalibrationError(data.source + ": the exponential fit did not converge (" +
                           to_string(fit.termination) + " after " + std::to_string(fit.iterations) +
                           " steps)");
  }
  cal.exponential.a = std::exp(fit.parameters(0));
  cal.exponential.b = std::exp(fit.parameters(1));
  if (cal.exponential.b * max_closure < kMinimumCurvature) {
    throw CalibrationError(data.source +
                           ": the joint closure shows no stiffening (the fitted exponential law "
                           "has b u_max = " +
                           format_value(cal.exponential.b * max_closure) +
                           " < 1e-3); the data call for the linear law");
  }
  try {
    cal.exponential.validate();
  } catch (const std::invalid_argument& e) {
    throw CalibrationError(data.source + ": the fitted exponential law is unusable: " + e.what());
  }
  cal.iterations = fit.iterations;
  cal.termination = to_string(fit.termination);
  if (m > 2) {
    ParameterUncertainty u;
    try {
      u = parameter_uncertainty(model.jacobian(fit.parameters), fit.residuals, fit.parameters);
    } catch (const std::invalid_argument& e) {
      throw CalibrationError(data.source +
                             ": no standard errors for the exponential fit: " + e.what());
    }
    cal.a_standard_error = cal.exponential.a * u.standard_errors(0);
    cal.b_standard_error = cal.exponential.b * u.standard_errors(1);
    cal.a_lower95 = std::exp(u.lower95(0));
    cal.a_upper95 = std::exp(u.upper95(0));
    cal.b_lower95 = std::exp(u.lower95(1));
    cal.b_upper95 = std::exp(u.upper95(1));
  }
  for (double s : stress) {
    cal.exponential_closure.push_back(exponential_closure(cal.exponential.a, cal.exponential.b, s));
  }
  cal.exponential_quality = fit_quality(closure, cal.exponential_closure);

  // 3. Linear law for comparison: minimise sum w_i^2 (sigma_i / k - u_i)^2 over 1/k.
  double su = 0.0;
  double ss = 0.0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    const double w2 = weight[i] * weight[i];
    su += w2 * stress[i] * closure[i];
    ss += w2 * stress[i] * stress[i];
  }
  if (!(su > 0.0 && ss > 0.0)) {
    throw CalibrationError(data.source + ": the linear comparison law is undetermined");
  }
  cal.linear.stiffness = ss / su;
  for (double s : stress) cal.linear_closure.push_back(s / cal.linear.stiffness);
  cal.linear_quality = fit_quality(closure, cal.linear_closure);
  return cal;
}

}  // namespace blockdem
