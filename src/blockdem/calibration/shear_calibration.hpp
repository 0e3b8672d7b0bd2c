// Calibration of the shear power laws (the paper's eqs 6-7) from direct shear tests at several
// normal stresses (its Figs 2-3): per curve, k_s,initial and u_peak from eq 5 integrated; then
// u_peak = C sigma_n^D and k_s,initial = A sigma_n^B fitted across the normal stresses.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "blockdem/calibration/calibration_data.hpp"
#include "blockdem/calibration/fit_quality.hpp"
#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

/// Eq 5 integrated along monotonic loading from zero: with k_s = (1 - u/u_peak) k_i (Pa/m),
/// tau(u) = k_i (u - u^2 / (2 u_peak)) for u < u_peak and k_i u_peak / 2 beyond, where
/// k_s reaches zero (Pa). k_i = k_s,initial (Pa/m), u_peak and u in m.
double degrading_shear_stress(double initial_stiffness, double peak_displacement, double u);

/// Eq 5 fitted to one curve.
struct PeakCurveFit {
  double normal_stress = 0.0;        ///< sigma_n (Pa)
  double initial_stiffness = 0.0;    ///< k_s,initial (Pa/m)
  double peak_displacement = 0.0;    ///< u_peak (m)
  double peak_shear_stress = 0.0;    ///< k_s,initial u_peak / 2 (Pa)
  std::size_t points_used = 0;       ///< rows used: pre-peak part and peak plateau (-)
  bool peak_within_data = false;     ///< u_peak <= the largest displacement used; else extrapolated
  FitQuality quality;                ///< residuals of eq 5 on the rows used (Pa)
  std::vector<double> model_stress;  ///< eq 5 with this curve's k_i, u_peak at every row (Pa)
  /// The calibrated law (power laws and cap) run through the kernel at every row (Pa).
  std::vector<double> law_stress;
  FitQuality law_quality;  ///< residuals of law_stress on every row of the curve (Pa)
  int iterations = 0;      ///< Levenberg-Marquardt steps (-)
  /// 95% intervals of k_s,initial (Pa/m) and u_peak (m) from the Jacobian at the optimum of the
  /// fit over (ln k_i, ln u_peak) (parameter_uncertainty; exp of the intervals in logs); 0 when
  /// only 2 rows were used.
  double initial_stiffness_lower95 = 0.0, initial_stiffness_upper95 = 0.0;
  double peak_displacement_lower95 = 0.0, peak_displacement_upper95 = 0.0;
};

/// Result of calibrate_shear.
struct ShearCalibration {
  std::vector<PeakCurveFit> curves;  ///< in the order of the data
  PowerLawFit stiffness;             ///< k_s,initial = A sigma_n^B (eq 7)
  PowerLawFit peak;                  ///< u_peak = C sigma_n^D (eq 6)
  /// The degrading law (eqs 5-7) with these power laws. Its Mohr-Coulomb cap friction_deg is
  /// the smallest angle whose cap stays at or above the law's own peak A C sigma_n^(B+D) / 2 at
  /// every tested normal stress: eq 5 data carry no friction information beyond the peaks, and
  /// a lower cap would cut the calibrated curves.
  DegradingShear law;
};

/// Calibrates eqs 6-7 from direct shear curves (the paper, p. 51, Figs 2-3). Per curve:
///  - the rows used are those up to and including the largest shear stress (the pre-peak part)
///    and the rows after it until the stress first falls more than 5 % below that peak (the
///    peak plateau of eq 5 within the scatter of the data; post-peak softening, which eq 5
///    lacks, is left out);
///  - eq 5 integrated (degrading_shear_stress) is fitted to them by Levenberg-Marquardt over
///    (ln k_i, ln u_peak), residuals relative to the measured shear stress (relative_weights),
///    started from the unweighted linear least-squares quadratic
///    tau = p1 u + p2 u^2 (k_i = p1, u_peak = -p1 / (2 p2)). The plateau beyond u_peak is part of
///    the model, so a row sampled just past the peak is fitted exactly.
/// Then fit_power_law of k_i and of u_peak against sigma_n.
/// Throws CalibrationError naming the file and the curve for: a curve without positive shear
/// stress; a peak reached before the 4th row; a fit that does not converge; u_peak more than 10
/// times the largest displacement used (no softening: u_peak undetermined); power laws the
/// degrading law rejects (e.g. a negative exponent).
ShearCalibration calibrate_shear(const DirectShearData& data);

}  // namespace blockdem
