// Calibration of the exponential normal joint law (the paper's eqs 3-4) from a column compression
// test (its Fig 1): intact deformation removed, closure per equivalent joint,
// sigma = a [exp(b u) - 1] fitted by Levenberg-Marquardt, with a linear law for comparison.
#pragma once

#include <string>
#include <vector>

#include "blockdem/calibration/calibration_data.hpp"
#include "blockdem/calibration/fit_quality.hpp"
#include "blockdem/contact/normal_laws.hpp"

namespace blockdem {

/// The column test: intact blocks and the number of equivalent joints. Defaults are the paper's
/// three-block column of 46 mm gypsum cubes (E = 5600 MPa, Table 1): two joints plus one
/// equivalent joint for the two end interfaces.
struct ColumnTestDef {
  double modulus = 5.6e9;  ///< E, Young's modulus of the intact blocks (Pa)
  double height = 0.138;   ///< H, total height of the intact blocks in the column (m)
  int joints = 3;          ///< N, number of equivalent joints the closure is shared by (-)

  /// Throws CalibrationError naming the parameter (modulus, height, joints) if it is not
  /// positive and finite (joints: not at least 1).
  void validate() const;
};

/// Result of calibrate_normal. Per-row vectors follow the data rows.
struct NormalCalibration {
  ColumnTestDef test;
  std::vector<double> stress;               ///< sigma (Pa)
  std::vector<double> displacement;         ///< measured shortening d (m)
  std::vector<double> intact_displacement;  ///< sigma H / E (m)
  std::vector<double> closure;              ///< u = (d - sigma H / E) / N, per joint (m)

  ExponentialNormal exponential;            ///< fitted sigma = a [exp(b u) - 1]
  std::vector<double> exponential_closure;  ///< ln(1 + sigma / a) / b at each row (m)
  FitQuality exponential_quality;           ///< in closure (m; relative: -)
  /// Standard errors of a (Pa) and b (1/m) at the optimum: the fit is over (ln a, ln b), whose
  /// covariance comes from the Jacobian (parameter_uncertainty); se(a) = a se(ln a) (delta
  /// method), likewise b.
  double a_standard_error = 0.0, b_standard_error = 0.0;
  /// 95% intervals of a (Pa) and b (1/m): exp of the intervals of ln a and ln b (asymmetric).
  double a_lower95 = 0.0, a_upper95 = 0.0, b_lower95 = 0.0, b_upper95 = 0.0;
  int iterations = 0;       ///< Levenberg-Marquardt steps (-)
  std::string termination;  ///< how Levenberg-Marquardt stopped

  LinearNormal linear;                 ///< fitted sigma = k u, for comparison
  std::vector<double> linear_closure;  ///< sigma / k at each row (m)
  FitQuality linear_quality;           ///< in closure (m; relative: -)
};

/// Calibrates the normal law from a column test (the paper, p. 50 and Fig 1(b)):
///  1. intact deformation sigma H / E subtracted from the measured displacement, the rest shared
///     by N equivalent joints: u = (d - sigma H / E) / N;
///  2. exponential law sigma = a [exp(b u) - 1] (eqs 3-4) fitted on the closure, because the
///     test controls the stress and measures the displacement: the residual of row i is
///     w_i [ln(1 + sigma_i / a) / b - u_i], relative to the measured closure (w_i from
///     relative_weights). Levenberg-Marquardt over (ln a, ln b), which keeps both positive,
///     started from a scan of b (for each b, a is linear in sigma-space);
///  3. linear law sigma = k u for comparison, the same residual:
///     1/k = sum(w^2 sigma u) / sum(w^2 sigma^2).
/// The implied tangent-stiffness form (eq 1) is k_n = k0 + c sigma with k0 = a b, c = b.
/// Throws CalibrationError: bad test parameters (naming them); a row whose closure is negative
/// (naming the row, the modulus and the height: the intact deformation exceeds the measurement);
/// no positive closure; data without stiffening (b u_max < 1e-3 at the best fit: use the linear
/// law); a fit that does not converge.
NormalCalibration calibrate_normal(const ColumnCompressionData& data, const ColumnTestDef& test);

}  // namespace blockdem
