// Shear-law parameters (Boon, Houlsby & Utili 2015, eqs 2, 5-8): validation, names, stiffness
// estimates for the time step, strength reduction, and construction from named scenario
// parameters, all driven by the tables of law_table.hpp.
#include "blockdem/contact/shear_laws.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blockdem/contact/law_table.hpp"
#include "blockdem/contact/overloaded.hpp"

namespace blockdem {

void LinearShear::validate() const {
  validate_law(*this);
}

void StressLinearShear::validate() const {
  validate_law(*this);
}

double ShearPowerLaws::initial_stiffness(double normal_stress) const {
  return stiffness_coefficient * std::pow(std::max(normal_stress, 0.0), stiffness_exponent);
}

double ShearPowerLaws::peak_displacement(double normal_stress) const {
  return peak_coefficient * std::pow(std::max(normal_stress, 0.0), peak_exponent);
}

void ShearPowerLaws::validate(std::string_view law) const {
  // The degrading law's table holds the keys of eqs 6-7; the strength has its own check.
  DegradingShear holder;
  holder.power_laws = *this;
  for (const auto& p : LawTraits<DegradingShear>::params) {
    check_range("shear", law, p.key, p.unit, p.range, p.get(holder));
  }
}

void DegradingShear::validate() const {
  validate_law(*this);
}

double ContinuouslyYieldingShear::friction_coefficient(double plastic_slip,
                                                       double peak_displacement) const {
  // Eq 8 with beta for u_s: mu0 [1 - exp(-beta/u_peak)], written with expm1 for small beta.
  return -strength.friction_coefficient * std::expm1(-plastic_slip / peak_displacement);
}

void ContinuouslyYieldingShear::validate() const {
  validate_law(*this);
}

void validate(const ShearLaw& law) {
  std::visit([](const auto& l) { l.validate(); }, law);
}

std::string law_name(const ShearLaw& law) {
  return std::visit(
      [](const auto& l) { return std::string(LawTraits<std::decay_t<decltype(l)>>::name); }, law);
}

std::string describe(const ShearLaw& law) {
  return std::visit([](const auto& l) { return describe_law(l); }, law);
}

const JointStrength& strength_of(const ShearLaw& law) {
  return std::visit([](const auto& l) -> const JointStrength& { return l.strength; }, law);
}

ShearLaw with_reduced_strength(const ShearLaw& law, double factor) {
  return std::visit(
      [factor](auto l) -> ShearLaw {
        l.strength = l.strength.reduced(factor);
        return l;
      },
      law);
}

double shear_stiffness_estimate(const ShearLaw& law, double normal_stress) {
  const double s = normal_stress;
  return std::visit(
      Overloaded{
          [](const LinearShear& l) { return l.stiffness; },
          [s](const StressLinearShear& l) { return l.stiffness(std::max(s, 0.0)); },
          [s](const DegradingShear& l) { return l.power_laws.initial_stiffness(s); },
          [s](const ContinuouslyYieldingShear& l) { return l.power_laws.initial_stiffness(s); },
      },
      law);
}

ShearLaw shear_law_from_params(std::string_view law, const std::map<std::string, double>& params) {
  return variant_from_params<ShearLaw>("shear", law, params);
}

}  // namespace blockdem
