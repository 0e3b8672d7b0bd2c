// Shear joint laws as pure kernels (Boon, Houlsby & Utili 2015, eqs 2 and 5-16): parameters per
// joint set, the closed set of laws, and the incremental update of one contact over one step.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <variant>

#include "blockdem/contact/joint_strength.hpp"
#include "blockdem/contact/shear_state.hpp"

namespace blockdem {

// Every shear law holds a JointStrength: its Mohr-Coulomb cap is |F| <= c A_c + F_n tan(phi)
// (tan(phi) stored, not the angle), with the tension cut-off and residual friction of
// joint_strength.hpp. The keys, units and ranges of every law are in law_table.hpp.

/// Constant shear stiffness with a Mohr-Coulomb cap (the paper's Table 2).
struct LinearShear {
  double stiffness = 1e9;  ///< k_s, shear stiffness per unit joint area (Pa/m)
  JointStrength strength;  ///< tan(phi), c, sigma_t, tan(phi_r)

  void validate() const;  ///< throws std::invalid_argument naming the law and the parameter
};

/// Stress-dependent stiffness k_s = k0 + c sigma_n (eq 2, Tsesarsky & Talesnick 2007) with a
/// Mohr-Coulomb cap.
struct StressLinearShear {
  double k0 = 1e8;         ///< stiffness at zero normal stress (Pa/m)
  double c = 9.7e4;        ///< growth of the stiffness with normal stress (1/m)
  JointStrength strength;  ///< tan(phi), c (cohesion), sigma_t, tan(phi_r)

  double stiffness(double normal_stress) const { return k0 + c * normal_stress; }  ///< (Pa/m)
  void validate() const;  ///< throws std::invalid_argument naming the law and the parameter
};

/// The power-law fits of the paper's eqs 6 and 7, sigma_n in Pa:
///   u_peak = C sigma_n^D (m, eq 6),   k_s,initial = A sigma_n^B (Pa/m, eq 7).
struct ShearPowerLaws {
  double stiffness_coefficient = 1.9e6;  ///< A (Pa^(1-B)/m)
  double stiffness_exponent = 0.7;       ///< B (-), >= 0
  double peak_coefficient = 2e-6;        ///< C (m Pa^(-D)), > 0 so that u_peak > 0
  double peak_exponent = 0.213;          ///< D (-), >= 0

  double initial_stiffness(double normal_stress) const;  ///< k_s,initial (Pa/m), eq 7
  double peak_displacement(double normal_stress) const;  ///< u_peak (m), eq 6
  /// Throws std::invalid_argument naming `law` and the parameter.
  void validate(std::string_view law) const;
};

/// Degrading stiffness k_s = (1 - u_s / u_peak) k_s,initial for u_s < u_peak, else 0 (eq 5), with
/// eqs 6-7 and a Mohr-Coulomb cap. u_s = |U_e|, the elastic shear displacement of ShearState:
/// it follows du while the joint sticks, is held on the sphere |U_e| = u_peak beyond it (the rest
/// of du is plastic), and is left unchanged by a step that ends on the Mohr-Coulomb cap (sliding).
/// Reversing du therefore unloads along the loading curve, and the joint never returns more energy
/// than it stored. The paper itself replaces this law by the continuously-yielding one for
/// general paths.
struct DegradingShear {
  ShearPowerLaws power_laws;  ///< eqs 6-7
  JointStrength strength;     ///< tan(phi) of the cap, c, sigma_t, tan(phi_r)

  void validate() const;  ///< throws std::invalid_argument naming the law and the parameter
};

/// Continuously-yielding (strain-hardening) friction, eq 8 with the Appendix's plastic slip:
/// mu(beta) = mu0 [1 - exp(-beta / u_peak)], mu0 = tan(phi), elastic stiffness k_s,initial
/// (eq 7), u_peak (eq 6), return mapping of eqs 9-16 solved for the current step's beta.
/// With cohesion the yield surface is |F| <= c A_c + mu(beta) F_n: at beta = 0 it is c A_c, so a
/// bonded joint breaks at its first plastic slip and then hardens towards tan(phi_r).
struct ContinuouslyYieldingShear {
  ShearPowerLaws power_laws;  ///< eqs 6-7
  JointStrength strength;     ///< mu0 = tan(phi), the friction reached at large slip; c, ...

  /// mu(beta) for plastic slip beta (m) and u_peak (m), eq 8 with mu0 = tan(phi) (-).
  double friction_coefficient(double plastic_slip, double peak_displacement) const;
  void validate() const;  ///< throws std::invalid_argument naming the law and the parameter
};

/// The closed set of shear laws.
using ShearLaw =
    std::variant<LinearShear, StressLinearShear, DegradingShear, ContinuouslyYieldingShear>;

/// Throws std::invalid_argument (message names the law and the parameter) if `law` is unusable.
void validate(const ShearLaw& law);
/// The law's key in scenario files: "linear", "stress_linear", "degrading",
/// "continuously_yielding".
std::string law_name(const ShearLaw& law);
/// One line with the formula and the parameter values, for run reports.
std::string describe(const ShearLaw& law);

/// The law's strength (every shear law has one).
const JointStrength& strength_of(const ShearLaw& law);
/// The law with every strength divided by `factor` F > 0: tan(phi)/F, c/F, sigma_t/F,
/// tan(phi_r)/F (JointStrength::reduced), for strength-reduction stability analyses. Stiffnesses
/// are unchanged. Throws std::invalid_argument unless F is finite and positive.
ShearLaw with_reduced_strength(const ShearLaw& law, double factor);

/// The largest elastic shear stiffness per area the law uses at normal stress sigma_n (Pa/m), for
/// the critical time step: k_s, k0 + c sigma_n, or k_s,initial (eq 7, zero at sigma_n = 0).
double shear_stiffness_estimate(const ShearLaw& law, double normal_stress);

/// Advances one contact by one time step: reads state (force already rotated into the current
/// tangent plane, see rotate_into_plane) and the increment, writes the new state.
/// Open joint (F_n <= 0 or sigma_n <= 0, and no intact bond): the force and U_e are reset to zero
/// and the plastic slip is kept; no friction acts, so the step counts as neither elastic nor
/// plastic.
/// Closed joint: trial force F_t = F_0 - k_s A_c du, then the law's yield condition with the
/// current strength (c, tan(phi) while intact; 0, tan(phi_r) once broken):
///  - linear, stress_linear, degrading: |F| <= c A_c + F_n tan(phi), radial return onto the cap;
///  - continuously_yielding: |F| <= c A_c + mu(beta) F_n, solved implicitly (see the .cpp).
/// A joint that can break (JointStrength::can_break) and is intact breaks for good
/// (state.bond) when sigma_n <= -sigma_t, or when the trial force leaves the intact yield
/// surface; that step is then taken again with the residual strength. An intact bonded joint in
/// tension (-sigma_t < sigma_n <= 0, F_n <= 0) keeps its shear force with the stiffness at zero
/// normal stress while |F| <= c A_c + F_n tan(phi).
/// The spring's energy, state.elastic_energy, changes by F·dF / k_s A over the step (zero once the
/// force is).
/// Throws std::invalid_argument for a non-finite increment, a non-unit normal, or a closed joint
/// with non-positive contact area.
ShearResult update_shear(const ShearLaw& law, ShearState& state, const ShearIncrement& increment);

/// Builds a shear law from a scenario table's named parameters (all values SI, angles in degrees),
/// the keys of law_table.hpp:
///   "linear":                stiffness (Pa/m)
///   "stress_linear":         k0 (Pa/m), c (1/m)
///   "degrading",
///   "continuously_yielding": stiffness_coefficient, stiffness_exponent, peak_coefficient,
///                            peak_exponent
/// and for every law friction_deg, cohesion (Pa), tensile_strength (Pa), residual_friction_deg.
/// Parameters not given keep the struct defaults (the paper's values). Throws
/// std::invalid_argument for an unknown law or parameter name, or a value validate() rejects.
ShearLaw shear_law_from_params(std::string_view law, const std::map<std::string, double>& params);

}  // namespace blockdem
