// Normal joint laws (Boon, Houlsby & Utili 2015, eqs 1, 3, 4): evaluation, validation, factories.
#include "blockdem/contact/normal_laws.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "blockdem/contact/law_table.hpp"
#include "blockdem/contact/overloaded.hpp"

namespace blockdem {
namespace {

/// E_n(x) = exp(x) - sum_{k<n} x^k / k!, the exponential with its first n Taylor terms removed,
/// for x >= 0. Direct subtraction loses all digits for small x, so |x| < 1 uses the series
/// sum_{k>=n} x^k / k!, whose terms fall faster than 1/k!.
double exp_remainder(int n, double x) {
  if (x < 1.0) {
    double term = 1.0;
    for (int k = 1; k <= n; ++k) term *= x / k;
    double sum = 0.0;
    for (int k = n; k < n + 30 && term != 0.0; ++k) {
      sum += term;
      if (std::abs(term) <= 1e-17 * std::abs(sum)) break;
      term *= x / (k + 1);
    }
    return sum;
  }
  double poly = 0.0;
  double term = 1.0;
  for (int k = 0; k < n; ++k) {
    poly += term;
    term *= x / (k + 1);
  }
  return std::exp(x) - poly;
}

}  // namespace

void LinearNormal::validate() const {
  validate_law(*this);
}

ExponentialNormal ExponentialNormal::from_tangent(double k0, double c) {
  // The tangent-stiffness form (eq 1): k0 and c, alternative keys of the exponential law.
  constexpr std::string_view law = LawTraits<ExponentialNormal>::name;
  check_range("normal", law, "k0", "Pa/m", ParamRange::positive, k0);
  check_range("normal", law, "c", "1/m", ParamRange::positive, c);
  return ExponentialNormal{k0 / c, c};
}

ExponentialNormal ExponentialNormal::eq3() {
  return from_tangent(4e9, 7.4e4);
}

ExponentialNormal ExponentialNormal::eq4() {
  return ExponentialNormal{0.5405e5, 3.7e4};
}

void ExponentialNormal::validate() const {
  validate_law(*this);
}

void validate(const NormalLaw& law) {
  std::visit([](const auto& l) { l.validate(); }, law);
}

std::string law_name(const NormalLaw& law) {
  return std::visit(
      [](const auto& l) { return std::string(LawTraits<std::decay_t<decltype(l)>>::name); }, law);
}

std::string describe(const NormalLaw& law) {
  return std::visit([](const auto& l) { return describe_law(l); }, law);
}

double normal_stress(const NormalLaw& law, double closure) {
  if (closure <= 0.0) return 0.0;
  return std::visit(
      Overloaded{
          [closure](const LinearNormal& l) { return l.stiffness * closure; },
          [closure](const ExponentialNormal& e) { return e.a * std::expm1(e.b * closure); },
      },
      law);
}

double normal_tangent_stiffness(const NormalLaw& law, double closure) {
  if (std::isnan(closure)) return closure;
  if (closure < 0.0) return 0.0;
  return std::visit(
      Overloaded{
          [](const LinearNormal& l) { return l.stiffness; },
          [closure](const ExponentialNormal& e) { return e.a * e.b * std::exp(e.b * closure); },
      },
      law);
}

double normal_stress_integral(const NormalLaw& law, double closure) {
  if (closure <= 0.0) return 0.0;
  return std::visit(
      Overloaded{
          [closure](const LinearNormal& l) { return 0.5 * l.stiffness * closure * closure; },
          [closure](const ExponentialNormal& e) {
            return e.a / e.b * exp_remainder(2, e.b * closure);
          },
      },
      law);
}

double normal_stress_second_integral(const NormalLaw& law, double closure) {
  if (closure <= 0.0) return 0.0;
  return std::visit(Overloaded{
                        [closure](const LinearNormal& l) {
                          return l.stiffness * closure * closure * closure / 6.0;
                        },
                        [closure](const ExponentialNormal& e) {
                          return e.a / (e.b * e.b) * exp_remainder(3, e.b * closure);
                        },
                    },
                    law);
}

double bonded_normal_stress(const NormalLaw& law, const JointStrength& strength, ShearState& state,
                            double closure) {
  if (closure > 0.0 || std::isnan(closure)) return normal_stress(law, closure);
  if (!strength.can_break() || state.bond != BondState::intact) return 0.0;
  // Tension branch: the zero-closure stiffness k_n(0) carried to negative closure.
  const double stress = normal_tangent_stiffness(law, 0.0) * closure;
  if (strength.tension_limit_reached(stress)) {
    state.bond = BondState::broken_in_tension;
    return 0.0;
  }
  return stress;
}

NormalLaw normal_law_from_params(std::string_view law, const std::map<std::string, double>& params,
                                 std::string_view preset) {
  if (law == LawTraits<ExponentialNormal>::name) {
    // Besides its table's keys (a, b), the exponential law takes eq 1's k0 and c, or a preset.
    std::vector<std::string_view> keys = law_keys<ExponentialNormal>();
    keys.insert(keys.end(), {"k0", "c"});
    check_known_params("normal", law, params, keys);
    if (!preset.empty()) {
      if (!params.empty()) {
        throw std::invalid_argument(
            law_error_prefix("normal", law) + "preset '" + std::string(preset) +
            "' cannot be combined with numeric parameters (got '" + params.begin()->first + "')");
      }
      if (preset == "eq3") return ExponentialNormal::eq3();
      if (preset == "eq4") return ExponentialNormal::eq4();
      throw std::invalid_argument(law_error_prefix("normal", law) + "unknown preset '" +
                                  std::string(preset) + "' (known: eq3, eq4)");
    }
    const bool has_ab = params.count("a") + params.count("b") > 0;
    const bool has_k0c = params.count("k0") + params.count("c") > 0;
    if (has_ab && has_k0c) {
      throw std::invalid_argument(law_error_prefix("normal", law) +
                                  "give either (a, b) or (k0, c), not both");
    }
    if (has_ab) require_pair("normal", law, params, "a", "b");
    if (has_k0c) {
      require_pair("normal", law, params, "k0", "c");
      return ExponentialNormal::from_tangent(params.at("k0"), params.at("c"));
    }
    return law_from_params<ExponentialNormal>(params);
  }
  if (!preset.empty() && law == LawTraits<LinearNormal>::name) {
    throw std::invalid_argument(law_error_prefix("normal", law) + "has no presets, got preset '" +
                                std::string(preset) + "'");
  }
  return variant_from_params<NormalLaw>("normal", law, params);
}

}  // namespace blockdem
