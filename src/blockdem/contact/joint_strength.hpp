// The strength of a joint (Mohr-Coulomb with a tension cut-off and a residual friction angle, as in
// the Coulomb slip model with residual strength of Itasca's 3DEC): parameters and bond predicates.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "blockdem/contact/law_param.hpp"
#include "blockdem/contact/law_params.hpp"

namespace blockdem {

/// Mohr-Coulomb strength of a joint with a tension cut-off. An intact joint carries shear up to
/// tau = c + sigma_n tan(phi) and normal stress down to sigma_n = -sigma_t (tension); when either
/// limit is reached at a contact it breaks for good and continues with c = 0, sigma_t = 0 and the
/// residual friction angle phi_r. The defaults (c = 0, sigma_t = 0, phi_r = phi) make a joint that
/// cannot break: it behaves exactly as a cohesionless Mohr-Coulomb joint.
/// Angles are stored as their tangents; degrees appear only in scenario files and reports.
/// The constructor is declared so that the struct is not an aggregate: a bare angle in braces
/// (LinearShear{1e9, 40.0}) does not compile, instead of silently becoming tan(phi) = 40.
struct JointStrength {
  JointStrength() = default;  ///< phi = 40 degrees, no cohesion, no tension
  /// Peak friction from degrees: tan(phi) is computed once here (the input edge).
  static JointStrength from_friction_deg(double friction_deg);

  double friction_coefficient = 0.8390996311772799;  ///< tan(phi) of the intact joint, > 0 (-)
  double cohesion = 0.0;                             ///< c, >= 0 (Pa)
  double tensile_strength = 0.0;                     ///< sigma_t, >= 0 (Pa)
  /// tan(phi_r) after breakage, in (0, tan(phi)]; empty: equal to tan(phi) (-).
  std::optional<double> residual_friction_coefficient;

  /// phi in degrees, for reports (degrees).
  double friction_deg() const { return friction_deg_from(friction_coefficient); }
  /// tan(phi_r): the residual coefficient, or the peak one when none is set (-).
  double residual_friction() const {
    return residual_friction_coefficient.value_or(friction_coefficient);
  }
  /// True when reaching a limit changes the joint (c > 0, sigma_t > 0 or phi_r < phi); a joint
  /// that cannot break is never marked broken.
  bool can_break() const;
  /// The tension cut-off: sigma_n <= -sigma_t (sigma_n in Pa, compression positive).
  bool tension_limit_reached(double normal_stress) const {
    return normal_stress <= -tensile_strength;
  }
  /// Throws std::invalid_argument naming `law` (e.g. "linear") and the scenario key.
  void validate(std::string_view law) const;
  /// The strength divided by `factor` F > 0 for strength reduction: tan(phi)/F and c/F as in
  /// Dawson, Roth & Drescher (1999, Geotechnique 49:835-840); here sigma_t/F and tan(phi_r)/F as
  /// well, so that every strength of the joint is reduced alike (their slopes have no tension
  /// cut-off and no residual angle). Throws std::invalid_argument unless F is finite and positive.
  JointStrength reduced(double factor) const;
};

/// The strength keys every shear law takes (scenario files, lab specs, calibration blocks).
inline constexpr std::array<LawParam<JointStrength>, 4> kStrengthParams{{
    {"friction_deg", "deg", "peak friction angle phi", ParamRange::friction_angle,
     [](const JointStrength& s) { return friction_deg_from(s.friction_coefficient); },
     [](JointStrength& s, double v) { s.friction_coefficient = friction_from_deg(v); }, true},
    {"cohesion", "Pa", "cohesion c", ParamRange::non_negative,
     [](const JointStrength& s) { return s.cohesion; },
     [](JointStrength& s, double v) { s.cohesion = v; }, true,
     [](const JointStrength& s) { return s.cohesion == 0.0; }},
    {"tensile_strength", "Pa", "tensile strength sigma_t", ParamRange::non_negative,
     [](const JointStrength& s) { return s.tensile_strength; },
     [](JointStrength& s, double v) { s.tensile_strength = v; }, true,
     [](const JointStrength& s) { return s.tensile_strength == 0.0; }},
    {"residual_friction_deg", "deg", "residual friction angle phi_r (default: phi)",
     ParamRange::friction_angle,
     [](const JointStrength& s) { return friction_deg_from(s.residual_friction()); },
     [](JointStrength& s, double v) { s.residual_friction_coefficient = friction_from_deg(v); },
     true, [](const JointStrength& s) { return s.residual_friction() == s.friction_coefficient; }},
}};

/// The strength a contact has now: intact, or broken (c = 0, sigma_t = 0, tan(phi_r)).
struct CurrentStrength {
  double friction_coefficient = 0.0;  ///< tan(phi) or tan(phi_r) (-)
  double cohesion = 0.0;              ///< c, or 0 once broken (Pa)
};

/// How a contact's bond stands. One byte: the shear state that holds it leaves the rest of its
/// last 8 bytes to the contact's flags and law (restart files write it as a 32-bit integer).
enum class BondState : std::uint8_t {
  intact,             ///< no limit reached yet (or the joint cannot break)
  broken_in_tension,  ///< sigma_n reached -sigma_t
  broken_in_shear,    ///< |tau| reached c + sigma_n tan(phi)
  /// Never bonded: a contact that formed after the start, between blocks that were not joined
  /// then (no rock bridge); it has the residual strength from the first step.
  unbonded,
};

/// "intact", "broken_in_tension" or "broken_in_shear".
const char* to_string(BondState state);

/// The strength for a bond in `state`.
CurrentStrength current_strength(const JointStrength& strength, BondState state);

}  // namespace blockdem
