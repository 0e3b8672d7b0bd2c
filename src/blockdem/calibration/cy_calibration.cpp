// Continuously-yielding law calibration with the engine's kernel as the model (see the header).
#include "blockdem/calibration/cy_calibration.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "blockdem/calibration/shear_path.hpp"
#include "blockdem/contact/law_params.hpp"
#include "blockdem/numerics/least_squares.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {
namespace {

// Friction coefficients beyond this (89.94 deg) are outside any rock joint; a trial step of the
// fit that reaches them is rejected (its residuals are NaN).
constexpr double kMaximumFrictionCoefficient = 1e3;

ContinuouslyYieldingShear make_law(const CyStiffnessDef& stiffness, double mu0,
                                   double peak_coefficient, double peak_exponent) {
  ContinuouslyYieldingShear law;
  law.power_laws.stiffness_coefficient = stiffness.stiffness_coefficient;
  law.power_laws.stiffness_exponent = stiffness.stiffness_exponent;
  law.power_laws.peak_coefficient = peak_coefficient;
  law.power_laws.peak_exponent = peak_exponent;
  law.strength.friction_coefficient = mu0;
  return law;
}

bool usable(double mu0, double peak_coefficient, double peak_exponent) {
  return mu0 > 0.0 && mu0 < kMaximumFrictionCoefficient && peak_coefficient > 0.0 &&
         std::isfinite(peak_coefficient) && std::isfinite(peak_exponent);
}

// Appends the relative residuals w_i (tau_model - tau_i) of one curve to r at offset `at`.
void curve_residuals(const ContinuouslyYieldingShear& law, const DirectShearCurve& curve,
                     const std::vector<double>& weight, Eigen::VectorXd& r, Eigen::Index at) {
  const std::vector<double> tau =
      simulate_monotonic_shear(law, curve.normal_stress, curve.displacement);
  for (std::size_t i = 0; i < tau.size(); ++i) {
    r(at + static_cast<Eigen::Index>(i)) = weight[i] * (tau[i] - curve.shear_stress[i]);
  }
}

Eigen::VectorXd not_a_number(Eigen::Index m) {
  return Eigen::VectorXd::Constant(m, std::numeric_limits<double>::quiet_NaN());
}

LeastSquaresModel with_numeric_jacobian(
    std::function<Eigen::VectorXd(const Eigen::VectorXd&)> residuals) {
  LeastSquaresModel model;
  model.residuals = residuals;
  model.jacobian = [residuals](const Eigen::VectorXd& p) {
    return finite_difference_jacobian(residuals, p);
  };
  return model;
}

// Step 1: eq 8 fitted to one curve alone, u_peak given directly (C = u_peak, D = 0).
CyCurveFit fit_single_curve(const DirectShearCurve& curve, const CyStiffnessDef& stiffness,
                            const std::string& name) {
  CyCurveFit fit;
  fit.normal_stress = curve.normal_stress;
  const auto top = std::max_element(curve.shear_stress.begin(), curve.shear_stress.end());
  const double tau_max = *top;
  if (!(tau_max > 0.0)) throw CalibrationError(name + " has no positive shear stress");
  const double k =
      stiffness.stiffness_coefficient * std::pow(curve.normal_stress, stiffness.stiffness_exponent);
  // u_peak guess: the plastic slip where tau first reaches (1 - 1/e) of its largest value.
  std::size_t row = 0;
  while (curve.shear_stress[row] < (1.0 - std::exp(-1.0)) * tau_max) ++row;
  const double u_row = curve.displacement[row];
  const double slip = u_row - curve.shear_stress[row] / k;
  const double peak_guess = slip > 0.0 ? slip : (u_row > 0.0 ? u_row : curve.displacement.back());
  const auto m = static_cast<Eigen::Index>(curve.displacement.size());
  const std::vector<double> weight = relative_weights(curve.shear_stress);
  const auto residuals = [&curve, &stiffness, &weight,
                          m](const Eigen::VectorXd& p) -> Eigen::VectorXd {
    const double mu0 = std::exp(p(0));
    const double peak = std::exp(p(1));
    if (!usable(mu0, peak, 0.0)) return not_a_number(m);
    Eigen::VectorXd r(m);
    curve_residuals(make_law(stiffness, mu0, peak, 0.0), curve, weight, r, 0);
    return r;
  };
  const LevenbergMarquardtResult result = levenberg_marquardt(
      with_numeric_jacobian(residuals),
      Eigen::Vector2d(std::log(tau_max / curve.normal_stress), std::log(peak_guess)));
  fit.friction_coefficient = std::exp(result.parameters(0));
  fit.peak_displacement = std::exp(result.parameters(1));
  fit.converged = result.converged();
  return fit;
}

}  // namespace

void CyStiffnessDef::validate() const {
  if (!(stiffness_coefficient > 0.0 && std::isfinite(stiffness_coefficient))) {
    throw CalibrationError(
        "stiffness_coefficient (A of eq 7, k_s,initial = A sigma_n^B) must be positive and "
        "finite, got " +
        format_value(stiffness_coefficient));
  }
  if (!(stiffness_exponent >= 0.0 && std::isfinite(stiffness_exponent))) {
    throw CalibrationError(
        "stiffness_exponent (B of eq 7, k_s,initial = A sigma_n^B) must be zero or positive and "
        "finite, got " +
        format_value(stiffness_exponent));
  }
}

CyCalibration calibrate_continuously_yielding(const DirectShearData& data,
                                              const CyStiffnessDef& stiffness) {
  stiffness.validate();
  if (data.curves.size() < kMinimumShearCurves) {
    throw CalibrationError(data.source + ": " + std::to_string(data.curves.size()) +
                           " normal stress(es); fitting eq 6 needs curves at at least " +
                           std::to_string(kMinimumShearCurves) + " different normal stresses");
  }
  CyCalibration cal;
  cal.stiffness = stiffness;

  // Step 1: every curve alone.
  std::vector<double> sigma;
  std::vector<double> peaks;
  double mean_mu = 0.0;
  for (const DirectShearCurve& curve : data.curves) {
    const std::string name = data.source + ":" + std::to_string(curve.lines.front()) +
                             ": the curve at normal stress " + format_value(curve.normal_stress) +
                             " Pa";
    cal.curves.push_back(fit_single_curve(curve, stiffness, name));
    sigma.push_back(curve.normal_stress);
    peaks.push_back(cal.curves.back().peak_displacement);
    mean_mu += cal.curves.back().friction_coefficient / static_cast<double>(data.curves.size());
  }
  cal.curve_peak_fit = fit_power_law(sigma, peaks, "u_peak (eq 6) of the single-curve fits");
  cal.reference_stress = cal.curve_peak_fit.reference_stress;

  // Step 2: all curves, parameters (ln mu0, ln u_ref, D).
  Eigen::Index m = 0;
  std::vector<std::vector<double>> weights;
  for (const DirectShearCurve& curve : data.curves) {
    m += static_cast<Eigen::Index>(curve.displacement.size());
    weights.push_back(relative_weights(curve.shear_stress));
  }
  const double reference_stress = cal.reference_stress;
  const auto residuals = [&data, &stiffness, &weights, m,
                          reference_stress](const Eigen::VectorXd& p) -> Eigen::VectorXd {
    const double mu0 = std::exp(p(0));
    const double exponent = p(2);
    const double coefficient = std::exp(p(1)) * std::pow(reference_stress, -exponent);
    if (!usable(mu0, coefficient, exponent)) return not_a_number(m);
    const ContinuouslyYieldingShear law = make_law(stiffness, mu0, coefficient, exponent);
    Eigen::VectorXd r(m);
    Eigen::Index at = 0;
    for (std::size_t c = 0; c < data.curves.size(); ++c) {
      curve_residuals(law, data.curves[c], weights[c], r, at);
      at += static_cast<Eigen::Index>(data.curves[c].displacement.size());
    }
    return r;
  };
  const Eigen::Vector3d start(std::log(mean_mu), std::log(cal.curve_peak_fit.reference_value),
                              cal.curve_peak_fit.exponent);
  const LevenbergMarquardtResult result =
      levenberg_marquardt(with_numeric_jacobian(residuals), start);
  if (!result.converged()) {
    throw CalibrationError(data.source + ": the continuously-yielding fit did not converge (" +
                           to_string(result.termination) + " after " +
                           std::to_string(result.iterations) + " steps)");
  }
  cal.iterations = result.iterations;
  cal.termination = to_string(result.termination);
  cal.friction_coefficient = std::exp(result.parameters(0));
  cal.reference_peak = std::exp(result.parameters(1));
  const double exponent = result.parameters(2);
  cal.law = make_law(stiffness, cal.friction_coefficient,
                     cal.reference_peak * std::pow(reference_stress, -exponent), exponent);
  try {
    cal.law.validate();
  } catch (const std::invalid_argument& e) {
    throw CalibrationError(data.source +
                           ": the fitted continuously-yielding law is unusable: " + e.what());
  }

  // Residuals of the calibrated law: per curve in Pa, overall in mobilised friction.
  std::vector<double> observed;
  std::vector<double> model;
  for (std::size_t c = 0; c < data.curves.size(); ++c) {
    const DirectShearCurve& curve = data.curves[c];
    CyCurveFit& fit = cal.curves[c];
    fit.law_stress = simulate_monotonic_shear(cal.law, curve.normal_stress, curve.displacement);
    fit.quality = fit_quality(curve.shear_stress, fit.law_stress);
    for (std::size_t i = 0; i < curve.shear_stress.size(); ++i) {
      observed.push_back(curve.shear_stress[i] / curve.normal_stress);
      model.push_back(fit.law_stress[i] / curve.normal_stress);
    }
  }
  cal.quality = fit_quality(observed, model);
  return cal;
}

}  // namespace blockdem
