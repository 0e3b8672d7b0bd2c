// Normal joint laws as pure kernels: stress, tangent stiffness and closed-form integrals over
// closure, for the linear and exponential laws of Boon, Houlsby & Utili (2015), eqs 1, 3 and 4.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <variant>

#include "blockdem/contact/joint_strength.hpp"
#include "blockdem/contact/shear_state.hpp"

namespace blockdem {

/// Linear normal law sigma_n = k_n u_n for u_n > 0, zero otherwise (the paper's Table 2).
struct LinearNormal {
  double stiffness = 10e9;  ///< k_n, normal stiffness per unit joint area (Pa/m)

  /// Throws std::invalid_argument naming the law and the parameter if a value is unusable.
  void validate() const;
};

/// Exponential normal law sigma_n = a [exp(b u_n) - 1] for u_n > 0, zero otherwise.
/// It is the integral of the tangent stiffness k_n = dsigma_n/du_n = k0 + c sigma_n with
/// a = k0 / c, b = c (the paper's eq 1 integrated into eq 3; eq 4 halves the stiffness).
/// The defaults are the paper's eq 4 ("half stiffness"), as printed.
struct ExponentialNormal {
  double a = 0.5405e5;  ///< stress scale a = k0 / c (Pa)
  double b = 3.7e4;     ///< closure rate b = c (1/m)

  /// From the tangent-stiffness form k_n = k0 + c sigma_n: k0 (Pa/m), c (1/m).
  static ExponentialNormal from_tangent(double k0, double c);
  /// Eq 3 as the integral of eq 1 (Tsesarsky & Talesnick 2007): k0 = 4e9 Pa/m, c = 7.4e4 1/m,
  /// so a = 54054.05... Pa (the paper prints it rounded as 0.5405e5).
  static ExponentialNormal eq3();
  /// Eq 4, "half stiffness", as printed: a = 0.5405e5 Pa, b = 3.7e4 1/m. Its stiffness at zero
  /// closure a b = 1.99985e9 Pa/m is the paper's rounding of 2e9 Pa/m (half of eq 3's 4e9).
  static ExponentialNormal eq4();

  double initial_stiffness() const {
    return a * b;
  }  ///< k0 = a b, stiffness at zero closure (Pa/m)

  /// Throws std::invalid_argument naming the law and the parameter if a value is unusable.
  void validate() const;
};

/// The closed set of normal laws.
using NormalLaw = std::variant<LinearNormal, ExponentialNormal>;

/// Throws std::invalid_argument (message names the law and the parameter) if `law` is unusable.
void validate(const NormalLaw& law);
/// The law's key in scenario files: "linear" or "exponential".
std::string law_name(const NormalLaw& law);
/// One line with the formula and the parameter values, for run reports.
std::string describe(const NormalLaw& law);

/// Normal stress sigma_n(u_n) (Pa) for closure u_n (m, compression positive); 0 for u_n <= 0.
/// Like every function below, it returns NaN for a NaN closure rather than hiding it.
/// The exponential law overflows to +inf for b u_n > ~709, a closure no joint survives; the
/// world's divergence check is expected to stop such a run.
double normal_stress(const NormalLaw& law, double closure);

/// Tangent stiffness dsigma_n/du_n (Pa/m): the right-hand derivative at u_n = 0 (k_n, resp.
/// a b) and 0 for u_n < 0. Use it at max(u_n, 0) for the critical time step.
double normal_tangent_stiffness(const NormalLaw& law, double closure);

/// First antiderivative Phi1(u) = integral_0^u sigma_n(s) ds (Pa m); 0 for u <= 0.
/// Linear: k u^2 / 2. Exponential: (a / b) [exp(b u) - 1 - b u], evaluated without cancellation.
double normal_stress_integral(const NormalLaw& law, double closure);

/// Second antiderivative Phi2(u) = integral_0^u Phi1(s) ds (Pa m^2); 0 for u <= 0.
/// Linear: k u^3 / 6. Exponential: (a / b^2) [exp(b u) - 1 - b u - (b u)^2 / 2].
/// Over a strip on which the closure varies linearly from u0 to u1 (u0 != u1), the mean stress is
/// (Phi1(u1) - Phi1(u0)) / (u1 - u0) and the mean of t sigma_n (t = 0 at u0, 1 at u1) is
/// [Phi1(u1) - (Phi2(u1) - Phi2(u0)) / (u1 - u0)] / (u1 - u0). For polygons use
/// integrate_normal_stress_over_polygon (normal_integral.hpp), which avoids the cancellation these
/// differences suffer when u1 - u0 is small.
double normal_stress_second_integral(const NormalLaw& law, double closure);

/// Normal stress of a joint that may be bonded (Pa, compression positive): normal_stress for
/// closure > 0. For closure <= 0 an intact joint that can break (JointStrength::can_break) carries
/// tension with the zero-closure stiffness, sigma_n = k_n(0) u_n (the linear tension branch of the
/// Coulomb slip model with tension cut-off), until sigma_n <= -sigma_t: then it breaks for good
/// (state.bond = broken_in_tension) and, like every open joint, returns 0.
double bonded_normal_stress(const NormalLaw& law, const JointStrength& strength, ShearState& state,
                            double closure);

/// Builds a normal law from a scenario table's named parameters (all values SI):
///   "linear":      stiffness (Pa/m)
///   "exponential": either a (Pa) and b (1/m), or k0 (Pa/m) and c (1/m), or a preset
/// `preset` ("eq3" or "eq4", exponential only) excludes numeric parameters. Parameters not given
/// keep the struct defaults. Throws std::invalid_argument for an unknown law, preset or parameter
/// name, an incomplete pair, or a value that validate() rejects.
NormalLaw normal_law_from_params(std::string_view law, const std::map<std::string, double>& params,
                                 std::string_view preset = {});

}  // namespace blockdem
