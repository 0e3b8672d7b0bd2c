// Shear-law parameters (Boon, Houlsby & Utili 2015, eqs 2, 5-8): validation, names, stiffness
// estimates for the time step, and construction from named scenario parameters.
#include "blockdem/contact/shear_laws.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"

namespace blockdem {
namespace {

[[noreturn]] void reject(std::string_view law, std::string_view name, double value,
                         std::string_view requirement) {
  throw std::invalid_argument(law_error_prefix("shear", law) + "parameter '" + std::string(name) +
                              "' must be " + std::string(requirement) + ", got " +
                              format_value(value));
}

void require_positive(std::string_view law, std::string_view name, double value,
                      std::string_view unit) {
  if (!(std::isfinite(value) && value > 0.0)) {
    reject(law, name, value, "a finite positive number (" + std::string(unit) + ")");
  }
}

void require_non_negative(std::string_view law, std::string_view name, double value,
                          std::string_view unit) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    reject(law, name, value, "a finite non-negative number (" + std::string(unit) + ")");
  }
}

void require_friction_angle(std::string_view law, double friction_deg) {
  if (!(std::isfinite(friction_deg) && friction_deg > 0.0 && friction_deg < 90.0)) {
    reject(law, "friction_deg", friction_deg, "an angle strictly between 0 and 90 degrees");
  }
}

double tan_deg(double degrees) {
  return std::tan(degrees * std::numbers::pi / 180.0);
}

}  // namespace

void LinearShear::validate() const {
  require_positive("linear", "stiffness", stiffness, "Pa/m");
  require_friction_angle("linear", friction_deg);
}

void StressLinearShear::validate() const {
  require_positive("stress_linear", "k0", k0, "Pa/m");
  require_non_negative("stress_linear", "c", c, "1/m");
  require_friction_angle("stress_linear", friction_deg);
}

double ShearPowerLaws::initial_stiffness(double normal_stress) const {
  return stiffness_coefficient * std::pow(std::max(normal_stress, 0.0), stiffness_exponent);
}

double ShearPowerLaws::peak_displacement(double normal_stress) const {
  return peak_coefficient * std::pow(std::max(normal_stress, 0.0), peak_exponent);
}

void ShearPowerLaws::validate(std::string_view law) const {
  require_positive(law, "stiffness_coefficient", stiffness_coefficient, "Pa^(1-B)/m");
  require_non_negative(law, "stiffness_exponent", stiffness_exponent, "-");
  // u_peak = C sigma_n^D must be positive for every closed joint.
  require_positive(law, "peak_coefficient", peak_coefficient, "m Pa^(-D), so that u_peak > 0");
  require_non_negative(law, "peak_exponent", peak_exponent, "-");
}

void DegradingShear::validate() const {
  power_laws.validate("degrading");
  require_friction_angle("degrading", friction_deg);
}

double ContinuouslyYieldingShear::friction_coefficient(double plastic_slip,
                                                       double peak_displacement) const {
  // Eq 8 with beta for u_s: mu0 [1 - exp(-beta/u_peak)], written with expm1 for small beta.
  return -tan_deg(friction_deg) * std::expm1(-plastic_slip / peak_displacement);
}

void ContinuouslyYieldingShear::validate() const {
  power_laws.validate("continuously_yielding");
  require_friction_angle("continuously_yielding", friction_deg);
}

void validate(const ShearLaw& law) {
  std::visit([](const auto& l) { l.validate(); }, law);
}

std::string law_name(const ShearLaw& law) {
  struct Name {
    std::string operator()(const LinearShear&) const { return "linear"; }
    std::string operator()(const StressLinearShear&) const { return "stress_linear"; }
    std::string operator()(const DegradingShear&) const { return "degrading"; }
    std::string operator()(const ContinuouslyYieldingShear&) const {
      return "continuously_yielding";
    }
  };
  return std::visit(Name{}, law);
}

std::string describe(const ShearLaw& law) {
  std::ostringstream out;
  out.precision(6);
  const auto power_text = [&out](const ShearPowerLaws& p) {
    out << "k_s,initial = " << p.stiffness_coefficient << " sigma_n^" << p.stiffness_exponent
        << " Pa/m (eq 7), u_peak = " << p.peak_coefficient << " sigma_n^" << p.peak_exponent
        << " m (eq 6)";
  };
  if (const auto* lin = std::get_if<LinearShear>(&law)) {
    out << "linear shear law k_s = " << lin->stiffness
        << " Pa/m, Mohr-Coulomb phi = " << lin->friction_deg << " deg";
  } else if (const auto* sl = std::get_if<StressLinearShear>(&law)) {
    out << "stress-linear shear law k_s = " << sl->k0 << " + " << sl->c
        << " sigma_n Pa/m (Boon et al. 2015 eq 2), Mohr-Coulomb phi = " << sl->friction_deg
        << " deg";
  } else if (const auto* deg = std::get_if<DegradingShear>(&law)) {
    out << "degrading shear law k_s = (1 - u_s/u_peak) k_s,initial (Boon et al. 2015 eq 5), ";
    power_text(deg->power_laws);
    out << ", Mohr-Coulomb phi = " << deg->friction_deg << " deg";
  } else {
    const auto& cy = std::get<ContinuouslyYieldingShear>(law);
    out << "continuously-yielding shear law mu = tan(" << cy.friction_deg
        << " deg) [1 - exp(-beta/u_peak)] (Boon et al. 2015 eq 8, Appendix eqs 9-16), ";
    power_text(cy.power_laws);
  }
  return out.str();
}

double shear_stiffness_estimate(const ShearLaw& law, double normal_stress) {
  if (const auto* lin = std::get_if<LinearShear>(&law)) return lin->stiffness;
  if (const auto* sl = std::get_if<StressLinearShear>(&law)) {
    return sl->stiffness(std::max(normal_stress, 0.0));
  }
  if (const auto* deg = std::get_if<DegradingShear>(&law)) {
    return deg->power_laws.initial_stiffness(normal_stress);
  }
  return std::get<ContinuouslyYieldingShear>(law).power_laws.initial_stiffness(normal_stress);
}

ShearLaw shear_law_from_params(std::string_view law, const std::map<std::string, double>& params) {
  const auto read_power_laws = [&params](ShearPowerLaws p) {
    p.stiffness_coefficient = param_or(params, "stiffness_coefficient", p.stiffness_coefficient);
    p.stiffness_exponent = param_or(params, "stiffness_exponent", p.stiffness_exponent);
    p.peak_coefficient = param_or(params, "peak_coefficient", p.peak_coefficient);
    p.peak_exponent = param_or(params, "peak_exponent", p.peak_exponent);
    return p;
  };
  ShearLaw result;
  if (law == "linear") {
    check_known_params("shear", law, params, {"stiffness", "friction_deg"});
    LinearShear l;
    l.stiffness = param_or(params, "stiffness", l.stiffness);
    l.friction_deg = param_or(params, "friction_deg", l.friction_deg);
    result = l;
  } else if (law == "stress_linear") {
    check_known_params("shear", law, params, {"k0", "c", "friction_deg"});
    StressLinearShear l;
    l.k0 = param_or(params, "k0", l.k0);
    l.c = param_or(params, "c", l.c);
    l.friction_deg = param_or(params, "friction_deg", l.friction_deg);
    result = l;
  } else if (law == "degrading" || law == "continuously_yielding") {
    check_known_params("shear", law, params,
                       {"stiffness_coefficient", "stiffness_exponent", "peak_coefficient",
                        "peak_exponent", "friction_deg"});
    if (law == "degrading") {
      DegradingShear l;
      l.power_laws = read_power_laws(l.power_laws);
      l.friction_deg = param_or(params, "friction_deg", l.friction_deg);
      result = l;
    } else {
      ContinuouslyYieldingShear l;
      l.power_laws = read_power_laws(l.power_laws);
      l.friction_deg = param_or(params, "friction_deg", l.friction_deg);
      result = l;
    }
  } else {
    throw std::invalid_argument("unknown shear law '" + std::string(law) +
                                "' (known: linear, stress_linear, degrading, "
                                "continuously_yielding)");
  }
  validate(result);
  return result;
}

}  // namespace blockdem
