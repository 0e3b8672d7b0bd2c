// The shear law's stiffness and friction for the torsional spring of a joint.
#include "blockdem/contact/twist_law.hpp"

#include <cmath>

#include "blockdem/contact/overloaded.hpp"

namespace blockdem {

TwistLawTerms twist_law_terms(const ShearLaw& law, const ShearState& state, double normal_stress) {
  TwistLawTerms terms;
  terms.shear_stiffness = shear_stiffness_estimate(law, normal_stress);
  const JointStrength& strength = strength_of(law);
  const double mu0 = state.broken() ? strength.residual_friction() : strength.friction_coefficient;
  terms.friction_coefficient =
      std::visit(Overloaded{[&](const ContinuouslyYieldingShear& l) {
                              const double peak = l.power_laws.peak_displacement(normal_stress);
                              return -mu0 * std::expm1(-state.plastic_slip / peak);
                            },
                            [&](const LinearShear&) { return mu0; },
                            [&](const StressLinearShear&) { return mu0; },
                            [&](const DegradingShear&) { return mu0; }},
                 law);
  return terms;
}

}  // namespace blockdem
