// Normal joint laws (Boon, Houlsby & Utili 2015, eqs 1, 3, 4): evaluation, validation, factories.
#include "blockdem/contact/normal_laws.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "blockdem/contact/law_params.hpp"

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

void require_positive(std::string_view law, std::string_view name, double value,
                      std::string_view unit) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(law_error_prefix("normal", law) + "parameter '" +
                                std::string(name) + "' must be a finite positive number (" +
                                std::string(unit) + "), got " + format_value(value));
  }
}

}  // namespace

void LinearNormal::validate() const {
  require_positive("linear", "stiffness", stiffness, "Pa/m");
}

ExponentialNormal ExponentialNormal::from_tangent(double k0, double c) {
  require_positive("exponential", "k0", k0, "Pa/m");
  require_positive("exponential", "c", c, "1/m");
  return ExponentialNormal{k0 / c, c};
}

ExponentialNormal ExponentialNormal::eq3() {
  return from_tangent(4e9, 7.4e4);
}

ExponentialNormal ExponentialNormal::eq4() {
  return ExponentialNormal{0.5405e5, 3.7e4};
}

void ExponentialNormal::validate() const {
  require_positive("exponential", "a", a, "Pa");
  require_positive("exponential", "b", b, "1/m");
}

void validate(const NormalLaw& law) {
  std::visit([](const auto& l) { l.validate(); }, law);
}

std::string law_name(const NormalLaw& law) {
  return std::holds_alternative<LinearNormal>(law) ? "linear" : "exponential";
}

std::string describe(const NormalLaw& law) {
  std::ostringstream out;
  out.precision(6);
  if (const auto* lin = std::get_if<LinearNormal>(&law)) {
    out << "linear normal law sigma_n = k_n u_n, k_n = " << lin->stiffness << " Pa/m";
  } else {
    const auto& e = std::get<ExponentialNormal>(law);
    out << "exponential normal law sigma_n = a [exp(b u_n) - 1] (Boon et al. 2015 eqs 3-4), a = "
        << e.a << " Pa, b = " << e.b << " 1/m, k_n = " << e.initial_stiffness() << " + " << e.b
        << " sigma_n Pa/m";
  }
  return out.str();
}

double normal_stress(const NormalLaw& law, double closure) {
  if (closure <= 0.0) return 0.0;
  if (const auto* lin = std::get_if<LinearNormal>(&law)) return lin->stiffness * closure;
  const auto& e = std::get<ExponentialNormal>(law);
  return e.a * std::expm1(e.b * closure);
}

double normal_tangent_stiffness(const NormalLaw& law, double closure) {
  if (std::isnan(closure)) return closure;
  if (closure < 0.0) return 0.0;
  if (const auto* lin = std::get_if<LinearNormal>(&law)) return lin->stiffness;
  const auto& e = std::get<ExponentialNormal>(law);
  return e.a * e.b * std::exp(e.b * closure);
}

double normal_stress_integral(const NormalLaw& law, double closure) {
  if (closure <= 0.0) return 0.0;
  if (const auto* lin = std::get_if<LinearNormal>(&law)) {
    return 0.5 * lin->stiffness * closure * closure;
  }
  const auto& e = std::get<ExponentialNormal>(law);
  return e.a / e.b * exp_remainder(2, e.b * closure);
}

double normal_stress_second_integral(const NormalLaw& law, double closure) {
  if (closure <= 0.0) return 0.0;
  if (const auto* lin = std::get_if<LinearNormal>(&law)) {
    return lin->stiffness * closure * closure * closure / 6.0;
  }
  const auto& e = std::get<ExponentialNormal>(law);
  return e.a / (e.b * e.b) * exp_remainder(3, e.b * closure);
}

NormalLaw normal_law_from_params(std::string_view law, const std::map<std::string, double>& params,
                                 std::string_view preset) {
  if (law == "linear") {
    if (!preset.empty()) {
      throw std::invalid_argument(law_error_prefix("normal", law) + "has no presets, got preset '" +
                                  std::string(preset) + "'");
    }
    check_known_params("normal", law, params, {"stiffness"});
    LinearNormal lin;
    lin.stiffness = param_or(params, "stiffness", lin.stiffness);
    lin.validate();
    return lin;
  }
  if (law == "exponential") {
    check_known_params("normal", law, params, {"a", "b", "k0", "c"});
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
    if (has_ab) {
      require_pair("normal", law, params, "a", "b");
      ExponentialNormal e{params.at("a"), params.at("b")};
      e.validate();
      return e;
    }
    if (has_k0c) {
      require_pair("normal", law, params, "k0", "c");
      return ExponentialNormal::from_tangent(params.at("k0"), params.at("c"));
    }
    return ExponentialNormal{};
  }
  throw std::invalid_argument("unknown normal law '" + std::string(law) +
                              "' (known: linear, exponential)");
}

}  // namespace blockdem
