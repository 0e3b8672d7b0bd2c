// Calibration of eqs 6-7 from direct shear curves through eq 5 (see the header for the method).
#include "blockdem/calibration/shear_calibration.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "blockdem/calibration/shear_path.hpp"
#include "blockdem/contact/law_params.hpp"
#include "blockdem/numerics/least_squares.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {
namespace {

// Rows up to the peak needed to fit two parameters and judge the fit.
constexpr std::size_t kMinimumPrePeakRows = 4;
// The peak plateau: rows after the largest shear stress are used while they stay within this
// fraction of it (eq 5 has a plateau; a larger drop is post-peak softening, which eq 5 lacks).
constexpr double kPlateauTolerance = 0.05;
// A fitted u_peak beyond this multiple of the largest displacement used is an extrapolation
// the data cannot support.
constexpr double kMaximumPeakExtrapolation = 10.0;

std::string curve_name(const DirectShearData& data, const DirectShearCurve& curve) {
  return data.source + ":" + std::to_string(curve.lines.front()) + ": the curve at normal stress " +
         format_value(curve.normal_stress) + " Pa";
}

// Starting (ln k_i, ln u_peak) from tau = p1 u + p2 u^2 fitted to the rows used.
Eigen::Vector2d starting_point(const std::vector<double>& u, const std::vector<double>& tau) {
  const auto m = static_cast<Eigen::Index>(u.size());
  Eigen::MatrixXd design(m, 2);
  Eigen::VectorXd observed(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const double x = u[static_cast<std::size_t>(i)];
    design(i, 0) = x;
    design(i, 1) = x * x;
    observed(i) = tau[static_cast<std::size_t>(i)];
  }
  const double u_last = u.back();
  const double tau_last = tau.back();
  double stiffness = 2.0 * tau_last / u_last;  // secant guess for a parabola peaking at u_last
  double peak = u_last;
  const LinearLeastSquaresSolution quadratic = solve_linear_least_squares(design, observed);
  const double p1 = quadratic.parameters(0);
  const double p2 = quadratic.parameters(1);
  if (p1 > 0.0 && p2 < 0.0) {
    stiffness = p1;
    peak = std::min(-p1 / (2.0 * p2), kMaximumPeakExtrapolation * u_last);
  }
  return Eigen::Vector2d(std::log(stiffness), std::log(peak));
}

PeakCurveFit fit_curve(const DirectShearData& data, const DirectShearCurve& curve) {
  const auto peak_row = static_cast<std::size_t>(
      std::max_element(curve.shear_stress.begin(), curve.shear_stress.end()) -
      curve.shear_stress.begin());
  if (!(curve.shear_stress[peak_row] > 0.0)) {
    throw CalibrationError(curve_name(data, curve) + " has no positive shear stress");
  }
  PeakCurveFit fit;
  fit.normal_stress = curve.normal_stress;
  // The rows used: up to the peak, then on while the stress stays within kPlateauTolerance of it.
  std::size_t last_row = peak_row;
  while (last_row + 1 < curve.shear_stress.size() &&
         curve.shear_stress[last_row + 1] >=
             (1.0 - kPlateauTolerance) * curve.shear_stress[peak_row]) {
    ++last_row;
  }
  fit.points_used = last_row + 1;
  if (peak_row + 1 < kMinimumPrePeakRows) {
    throw CalibrationError(curve_name(data, curve) + " peaks at row " +
                           std::to_string(curve.lines[peak_row]) + ", after " +
                           std::to_string(peak_row + 1) + " rows; fitting eq 5 needs at least " +
                           std::to_string(kMinimumPrePeakRows) + " rows up to the peak");
  }
  const std::vector<double> u(curve.displacement.begin(),
                              curve.displacement.begin() + static_cast<long>(fit.points_used));
  const std::vector<double> tau(curve.shear_stress.begin(),
                                curve.shear_stress.begin() + static_cast<long>(fit.points_used));
  const auto m = static_cast<Eigen::Index>(u.size());
  const std::vector<double> weight = relative_weights(tau);

  // Eq 5 integrated over (ln k_i, ln u_peak); residuals relative to the measured stress.
  LeastSquaresModel model;
  model.residuals = [&](const Eigen::VectorXd& p) {
    const double k = std::exp(p(0));
    const double up = std::exp(p(1));
    Eigen::VectorXd r(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto j = static_cast<std::size_t>(i);
      r(i) = weight[j] * (degrading_shear_stress(k, up, u[j]) - tau[j]);
    }
    return r;
  };
  model.jacobian = [&](const Eigen::VectorXd& p) {
    const double k = std::exp(p(0));
    const double up = std::exp(p(1));
    Eigen::MatrixXd jac(m, 2);
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto j = static_cast<std::size_t>(i);
      const double x = u[j];
      // d tau / d ln k = tau; d tau / d ln u_peak = k u^2 / (2 u_peak) before the peak and
      // k u_peak / 2 on the plateau (equal at u = u_peak: the model is C1).
      jac(i, 0) = weight[j] * degrading_shear_stress(k, up, x);
      jac(i, 1) = weight[j] * (x < up ? k * x * x / (2.0 * up) : 0.5 * k * up);
    }
    return jac;
  };
  const LevenbergMarquardtResult result = levenberg_marquardt(model, starting_point(u, tau));
  if (!result.converged()) {
    throw CalibrationError(curve_name(data, curve) + ": the eq 5 fit did not converge (" +
                           to_string(result.termination) + " after " +
                           std::to_string(result.iterations) + " steps)");
  }
  fit.initial_stiffness = std::exp(result.parameters(0));
  fit.peak_displacement = std::exp(result.parameters(1));
  fit.peak_shear_stress = 0.5 * fit.initial_stiffness * fit.peak_displacement;
  fit.iterations = result.iterations;
  // No softening first: with u_peak far beyond the data its column of J vanishes, and the
  // intervals below would only say that J is rank deficient.
  if (fit.peak_displacement > kMaximumPeakExtrapolation * u.back()) {
    throw CalibrationError(curve_name(data, curve) + " shows no softening up to row " +
                           std::to_string(curve.lines[last_row]) +
                           ": the fitted u_peak = " + format_value(fit.peak_displacement) +
                           " m is more than " + format_value(kMaximumPeakExtrapolation) +
                           " times the largest displacement, so eq 5 cannot determine it");
  }
  if (m > 2) {
    ParameterUncertainty un;
    try {
      un = parameter_uncertainty(model.jacobian(result.parameters), result.residuals,
                                 result.parameters);
    } catch (const std::invalid_argument& e) {
      throw CalibrationError(curve_name(data, curve) +
                             ": no intervals for the eq 5 fit: " + e.what());
    }
    fit.initial_stiffness_lower95 = std::exp(un.lower95(0));
    fit.initial_stiffness_upper95 = std::exp(un.upper95(0));
    fit.peak_displacement_lower95 = std::exp(un.lower95(1));
    fit.peak_displacement_upper95 = std::exp(un.upper95(1));
  }
  fit.peak_within_data = fit.peak_displacement <= u.back();
  std::vector<double> model_used;
  for (double x : curve.displacement) {
    fit.model_stress.push_back(
        degrading_shear_stress(fit.initial_stiffness, fit.peak_displacement, x));
  }
  model_used.assign(fit.model_stress.begin(),
                    fit.model_stress.begin() + static_cast<long>(fit.points_used));
  fit.quality = fit_quality(tau, model_used);
  return fit;
}

}  // namespace

double degrading_shear_stress(double initial_stiffness, double peak_displacement, double u) {
  if (u >= peak_displacement) return 0.5 * initial_stiffness * peak_displacement;
  return initial_stiffness * (u - u * u / (2.0 * peak_displacement));
}

ShearCalibration calibrate_shear(const DirectShearData& data) {
  if (data.curves.size() < kMinimumShearCurves) {
    throw CalibrationError(data.source + ": " + std::to_string(data.curves.size()) +
                           " normal stress(es); fitting eqs 6-7 needs curves at at least " +
                           std::to_string(kMinimumShearCurves) + " different normal stresses");
  }
  ShearCalibration cal;
  std::vector<double> sigma;
  std::vector<double> stiffness;
  std::vector<double> peak;
  for (const DirectShearCurve& curve : data.curves) {
    cal.curves.push_back(fit_curve(data, curve));
    sigma.push_back(curve.normal_stress);
    stiffness.push_back(cal.curves.back().initial_stiffness);
    peak.push_back(cal.curves.back().peak_displacement);
  }
  cal.stiffness = fit_power_law(sigma, stiffness, "k_s,initial (eq 7)");
  cal.peak = fit_power_law(sigma, peak, "u_peak (eq 6)");

  ShearPowerLaws laws;
  laws.stiffness_coefficient = cal.stiffness.coefficient;
  laws.stiffness_exponent = cal.stiffness.exponent;
  laws.peak_coefficient = cal.peak.coefficient;
  laws.peak_exponent = cal.peak.exponent;
  try {
    laws.validate("degrading");
  } catch (const std::invalid_argument& e) {
    throw CalibrationError(data.source + ": the fitted power laws are unusable: " + e.what());
  }
  // The cap: the largest ratio of the law's peak to the normal stress over the tested stresses.
  double ratio = 0.0;
  for (double s : sigma) {
    ratio = std::max(ratio, 0.5 * laws.initial_stiffness(s) * laws.peak_displacement(s) / s);
  }
  cal.law.power_laws = laws;
  cal.law.strength.friction_coefficient = ratio;
  try {
    cal.law.validate();
  } catch (const std::invalid_argument& e) {
    throw CalibrationError(data.source + ": the fitted degrading law is unusable: " + e.what());
  }
  // Round trip: the calibrated law through the kernel at every row.
  for (std::size_t c = 0; c < data.curves.size(); ++c) {
    PeakCurveFit& fit = cal.curves[c];
    fit.law_stress = simulate_monotonic_shear(cal.law, data.curves[c].normal_stress,
                                              data.curves[c].displacement);
    fit.law_quality = fit_quality(data.curves[c].shear_stress, fit.law_stress);
  }
  return cal;
}

}  // namespace blockdem
