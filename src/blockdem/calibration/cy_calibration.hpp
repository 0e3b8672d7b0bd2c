// Calibration of the continuously-yielding shear law (the paper's eq 8 with eq 6 and the
// Appendix) from direct shear curves (its Fig 4): friction mu0 = tan(phi) and the u_peak power
// law fitted with the model curves produced by the engine's own kernel (update_shear).
#pragma once

#include <string>
#include <vector>

#include "blockdem/calibration/calibration_data.hpp"
#include "blockdem/calibration/fit_quality.hpp"
#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

/// The elastic stiffness the fit holds fixed: k_s,initial = A sigma_n^B (eq 7), e.g. from
/// calibrate_shear. Defaults are the paper's eq 7.
struct CyStiffnessDef {
  double stiffness_coefficient = 1.9e6;  ///< A (Pa^(1-B)/m), > 0
  double stiffness_exponent = 0.7;       ///< B (-), >= 0

  /// Throws CalibrationError naming the parameter if A is not positive and finite or B is
  /// negative or not finite.
  void validate() const;
};

/// One curve: eq 8 fitted to it alone (a diagnostic and the starting point) and the residuals
/// of the calibrated law.
struct CyCurveFit {
  double normal_stress = 0.0;         ///< sigma_n (Pa)
  double friction_coefficient = 0.0;  ///< mu0 fitted to this curve alone (-)
  double peak_displacement = 0.0;     ///< u_peak fitted to this curve alone (m)
  bool converged = false;             ///< the single-curve fit converged
  std::vector<double> law_stress;     ///< the calibrated law through the kernel at every row (Pa)
  FitQuality quality;                 ///< residuals of law_stress (Pa)
};

/// Result of calibrate_continuously_yielding.
struct CyCalibration {
  CyStiffnessDef stiffness;           ///< the fixed k_s,initial law
  ContinuouslyYieldingShear law;      ///< fitted: tan(phi), peak_coefficient, peak_exponent
  double friction_coefficient = 0.0;  ///< mu0 = tan(friction_deg) (-)
  double reference_stress = 0.0;      ///< sigma_ref, geometric mean of the normal stresses (Pa)
  double reference_peak = 0.0;        ///< u_peak at sigma_ref (m)
  PowerLawFit curve_peak_fit;         ///< C, D from the single-curve u_peaks (the starting point)
  std::vector<CyCurveFit> curves;     ///< in the order of the data
  FitQuality quality;                 ///< all rows, in mobilised friction tau / sigma_n (-)
  int iterations = 0;                 ///< Levenberg-Marquardt steps of the global fit (-)
  std::string termination;            ///< how the global fit stopped
};

/// Fits mu0 = tan(phi) and u_peak = C sigma_n^D (eqs 6, 8) to direct shear curves, k_s,initial
/// held at `stiffness`. The model curve of each normal stress is simulate_monotonic_shear of the
/// ContinuouslyYieldingShear law (one kernel step per data interval: the kernel's implicit
/// update is exact for this path at any step size). Residuals are relative to the measured
/// shear stress (relative_weights per curve), so every curve weighs alike whatever its normal
/// stress.
///  1. Each curve alone: Levenberg-Marquardt over (ln mu0, ln u_peak), finite-difference
///     Jacobian, started from mu0 = max tau / sigma_n and u_peak = the plastic slip
///     u - tau / k_i where tau first reaches 63 % (1 - 1/e) of its maximum.
///  2. All curves: Levenberg-Marquardt over (ln mu0, ln u_ref, D) with
///     u_peak = u_ref (sigma_n / sigma_ref)^D, sigma_ref the geometric mean of the normal
///     stresses (so ln u_ref and D are uncorrelated), started from the mean of the mu0s and
///     fit_power_law of the u_peaks; C = u_ref sigma_ref^-D.
/// Throws CalibrationError for bad stiffness parameters, a curve without positive shear stress,
/// a global fit that does not converge, or a law the kernel rejects (e.g. D < 0, phi >= 90 deg).
CyCalibration calibrate_continuously_yielding(const DirectShearData& data,
                                              const CyStiffnessDef& stiffness);

}  // namespace blockdem
