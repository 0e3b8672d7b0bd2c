// Goodness of fit of a calibrated curve against measured values, and the power-law fits of the
// paper's eqs 6 and 7 (y = coefficient * sigma_n^exponent) by linear least squares in logs.
#pragma once

#include <string>
#include <vector>

namespace blockdem {

/// The floor of relative_weights, as a fraction of the largest measured value (-).
inline constexpr double kRelativeWeightFloor = 0.01;

/// Weights of relative residuals: w_i = 1 / max(|y_i|, kRelativeWeightFloor max_j |y_j|), so
/// that w_i (model_i - y_i) is the misfit relative to the measured value. Every calibration fit
/// minimises sum (w_i r_i)^2: the maximum-likelihood fit when measurement errors are
/// proportional to the measured value (as in tools/make_synthetic_calibration_data.py), and one
/// that lets the small-displacement rows (which fix the initial stiffnesses) count as much as
/// the large ones. The floor keeps rows measured as zero finite. Throws std::invalid_argument if
/// every value is zero or one is not finite.
std::vector<double> relative_weights(const std::vector<double>& observed);

/// Residuals r_i = model_i - observed_i summarised. Units are those of the fitted quantity.
struct FitQuality {
  double r_squared = 0.0;              ///< 1 - sum r^2 / sum (obs - mean obs)^2 (-)
  double rms_residual = 0.0;           ///< sqrt(mean r^2) (fitted units)
  double max_abs_residual = 0.0;       ///< max |r| (fitted units)
  double rms_relative_residual = 0.0;  ///< sqrt(mean (w r)^2), w from relative_weights (-)
  std::vector<double> residuals;       ///< model - observed, per point (fitted units)
};

/// FitQuality of `model` against `observed` (same size, at least 2 values). R^2 is -inf when
/// the observations are all equal and the model misses them, 1 when it hits them exactly.
/// Throws std::invalid_argument if the sizes differ or are below 2.
FitQuality fit_quality(const std::vector<double>& observed, const std::vector<double>& model);

/// y = coefficient * sigma^exponent, fitted as ln y = ln y_ref + exponent ln(sigma / sigma_ref)
/// with sigma_ref the geometric mean of the sigmas, so that the two parameters of the linear
/// problem are uncorrelated. The coefficient is y_ref sigma_ref^(-exponent).
struct PowerLawFit {
  double coefficient = 0.0;       ///< y at sigma = 1 Pa (units of y per Pa^exponent)
  double exponent = 0.0;          ///< (-)
  double reference_stress = 0.0;  ///< sigma_ref, geometric mean of the stresses fitted (Pa)
  double reference_value = 0.0;   ///< y at sigma_ref (units of y)
  double r_squared = 0.0;         ///< R^2 of ln y (-)
  double rms_log_residual = 0.0;  ///< RMS of ln y_fit - ln y: relative scatter (-)
  /// With 3 or more points (else 0): the exponent's standard error and 95% interval, and the
  /// 95% interval of reference_value, from the covariance of the fit in ln y
  /// (parameter_uncertainty; the interval of y_ref is exp of that of ln y_ref).
  double exponent_standard_error = 0.0;                                 ///< (-)
  double exponent_lower95 = 0.0, exponent_upper95 = 0.0;                ///< (-)
  double reference_value_lower95 = 0.0, reference_value_upper95 = 0.0;  ///< (units of y)

  /// coefficient * sigma^exponent, evaluated as y_ref (sigma / sigma_ref)^exponent.
  double evaluate(double sigma) const;
};

/// Fits y = coefficient * sigma^exponent by column-pivoted QR on (1, ln(sigma / sigma_ref)).
/// `what` names the quantity in messages (e.g. "u_peak (eq 6)"). Throws CalibrationError if
/// there are fewer than 2 points, fewer than 2 distinct stresses, or a value is not positive
/// and finite (the message gives the stress).
PowerLawFit fit_power_law(const std::vector<double>& stress, const std::vector<double>& value,
                          const std::string& what);

}  // namespace blockdem
