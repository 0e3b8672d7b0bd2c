// What a shear law gives the torsional spring of a joint (contact/twist.hpp) at one step: the
// shear stiffness per area and the friction coefficient in force at the joint's current state.
#pragma once

#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

struct TwistLawTerms {
  double shear_stiffness = 0.0;       ///< k_s per unit area at this step's σ_n (Pa/m)
  double friction_coefficient = 0.0;  ///< μ of the cap at the joint's state (-)
};

/// k_s = shear_stiffness_estimate(law, σ_n) (the elastic stiffness; for the degrading law its
/// initial value, eq 7, since the twist spring keeps no u_s of its own); μ = tan φ while the bond
/// is intact, tan φ_r once broken, and for the continuously-yielding law μ(β) of eq 8 with the
/// contact's accumulated plastic slip β and u_peak(σ_n) (eq 6). The cohesion is not part of the
/// twist cap (a bonded joint resists twist by friction only: on the safe side).
TwistLawTerms twist_law_terms(const ShearLaw& law, const ShearState& state, double normal_stress);

}  // namespace blockdem
