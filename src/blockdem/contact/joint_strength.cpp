// Joint strength (Mohr-Coulomb with tension cut-off and residual friction): validation, bond
// predicates and strength reduction.
#include "blockdem/contact/joint_strength.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "blockdem/contact/law_params.hpp"

namespace blockdem {

JointStrength JointStrength::from_friction_deg(double friction_deg) {
  JointStrength s;
  s.friction_coefficient = friction_from_deg(friction_deg);
  return s;
}

bool JointStrength::can_break() const {
  return cohesion > 0.0 || tensile_strength > 0.0 || residual_friction() < friction_coefficient;
}

void JointStrength::validate(std::string_view law) const {
  for (const auto& p : kStrengthParams)
    check_range("shear", law, p.key, p.unit, p.range, p.get(*this));
  // Residual friction above the peak is not a residual strength.
  if (residual_friction() > friction_coefficient) {
    const auto& residual = kStrengthParams[3];
    throw std::invalid_argument(law_error_prefix("shear", law) + "parameter '" +
                                std::string(residual.key) + "' must be at most " +
                                std::string(kStrengthParams[0].key) + " (" +
                                format_value(kStrengthParams[0].get(*this)) + " deg), got " +
                                format_value(residual.get(*this)));
  }
}

JointStrength JointStrength::reduced(double factor) const {
  if (!(std::isfinite(factor) && factor > 0.0)) {
    throw std::invalid_argument("strength reduction factor must be finite and positive, got " +
                                format_value(factor));
  }
  JointStrength s = *this;
  s.friction_coefficient = friction_coefficient / factor;
  s.cohesion = cohesion / factor;
  s.tensile_strength = tensile_strength / factor;
  if (residual_friction_coefficient) {
    s.residual_friction_coefficient = *residual_friction_coefficient / factor;
  }
  return s;
}

const char* to_string(BondState state) {
  switch (state) {
    case BondState::intact:
      return "intact";
    case BondState::broken_in_tension:
      return "broken_in_tension";
    case BondState::broken_in_shear:
      return "broken_in_shear";
    case BondState::unbonded:
      return "unbonded";
  }
  throw std::logic_error("to_string(BondState): value out of range");
}

CurrentStrength current_strength(const JointStrength& strength, BondState state) {
  if (state == BondState::intact) return {strength.friction_coefficient, strength.cohesion};
  return {strength.residual_friction(), 0.0};
}

}  // namespace blockdem
