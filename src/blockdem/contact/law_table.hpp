// One table per joint law (name, formula and citation, keys with units, ranges and which keys are
// strengths), and the generic code it drives: reading named parameters, validation, the values
// writers print (calibration blocks, reports) and describe().
#pragma once

#include <array>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/joint_strength.hpp"
#include "blockdem/contact/law_param.hpp"
#include "blockdem/contact/law_params.hpp"
#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"

namespace blockdem {

/// Specialised once per law: kind ("normal", "shear"), name (the scenario key), formula (with its
/// citation, for describe()) and params (the law's own keys; shear laws add kStrengthParams).
template <class Law>
struct LawTraits;

template <>
struct LawTraits<LinearNormal> {
  static constexpr std::string_view kind = "normal";
  static constexpr std::string_view name = "linear";
  static constexpr std::string_view formula = "linear normal law sigma_n = k_n u_n";
  static constexpr std::array<LawParam<LinearNormal>, 1> params{{
      {"stiffness", "Pa/m", "normal stiffness k_n", ParamRange::stiffness,
       [](const LinearNormal& l) { return l.stiffness; },
       [](LinearNormal& l, double v) { l.stiffness = v; }},
  }};
};

template <>
struct LawTraits<ExponentialNormal> {
  static constexpr std::string_view kind = "normal";
  static constexpr std::string_view name = "exponential";
  static constexpr std::string_view formula =
      "exponential normal law sigma_n = a [exp(b u_n) - 1], k_n = a b + b sigma_n "
      "(Boon et al. 2015 eqs 1, 3-4)";
  static constexpr std::array<LawParam<ExponentialNormal>, 2> params{{
      {"a", "Pa", "stress scale a = k0 / c", ParamRange::positive,
       [](const ExponentialNormal& l) { return l.a; },
       [](ExponentialNormal& l, double v) { l.a = v; }},
      {"b", "1/m", "closure rate b = c", ParamRange::positive,
       [](const ExponentialNormal& l) { return l.b; },
       [](ExponentialNormal& l, double v) { l.b = v; }},
  }};
};

template <>
struct LawTraits<LinearShear> {
  static constexpr std::string_view kind = "shear";
  static constexpr std::string_view name = "linear";
  static constexpr std::string_view formula =
      "linear shear law, constant k_s (Boon et al. 2015 "
      "Table 2)";
  static constexpr std::array<LawParam<LinearShear>, 1> params{{
      {"stiffness", "Pa/m", "shear stiffness k_s", ParamRange::stiffness,
       [](const LinearShear& l) { return l.stiffness; },
       [](LinearShear& l, double v) { l.stiffness = v; }},
  }};
};

template <>
struct LawTraits<StressLinearShear> {
  static constexpr std::string_view kind = "shear";
  static constexpr std::string_view name = "stress_linear";
  static constexpr std::string_view formula =
      "stress-linear shear law k_s = k0 + c sigma_n (Boon et al. 2015 eq 2)";
  static constexpr std::array<LawParam<StressLinearShear>, 2> params{{
      {"k0", "Pa/m", "shear stiffness at zero normal stress", ParamRange::stiffness,
       [](const StressLinearShear& l) { return l.k0; },
       [](StressLinearShear& l, double v) { l.k0 = v; }},
      {"c", "1/m", "growth of the stiffness with normal stress", ParamRange::non_negative,
       [](const StressLinearShear& l) { return l.c; },
       [](StressLinearShear& l, double v) { l.c = v; }},
  }};
};

/// The keys of eqs 6-7, shared by the degrading and continuously-yielding laws.
template <class Law>
constexpr std::array<LawParam<Law>, 4> power_law_params() {
  return {{
      {"stiffness_coefficient", "Pa^(1-B)/m", "A of k_s,initial = A sigma_n^B (eq 7)",
       ParamRange::positive, [](const Law& l) { return l.power_laws.stiffness_coefficient; },
       [](Law& l, double v) { l.power_laws.stiffness_coefficient = v; }},
      {"stiffness_exponent", "-", "B of eq 7", ParamRange::non_negative,
       [](const Law& l) { return l.power_laws.stiffness_exponent; },
       [](Law& l, double v) { l.power_laws.stiffness_exponent = v; }},
      {"peak_coefficient", "m Pa^(-D)", "C of u_peak = C sigma_n^D (eq 6), so that u_peak > 0",
       ParamRange::positive, [](const Law& l) { return l.power_laws.peak_coefficient; },
       [](Law& l, double v) { l.power_laws.peak_coefficient = v; }},
      {"peak_exponent", "-", "D of eq 6", ParamRange::non_negative,
       [](const Law& l) { return l.power_laws.peak_exponent; },
       [](Law& l, double v) { l.power_laws.peak_exponent = v; }},
  }};
}

template <>
struct LawTraits<DegradingShear> {
  static constexpr std::string_view kind = "shear";
  static constexpr std::string_view name = "degrading";
  static constexpr std::string_view formula =
      "degrading shear law k_s = (1 - u_s/u_peak) k_s,initial (Boon et al. 2015 eqs 5-7)";
  static constexpr auto params = power_law_params<DegradingShear>();
};

template <>
struct LawTraits<ContinuouslyYieldingShear> {
  static constexpr std::string_view kind = "shear";
  static constexpr std::string_view name = "continuously_yielding";
  static constexpr std::string_view formula =
      "continuously-yielding shear law mu = tan(phi) [1 - exp(-beta/u_peak)] (Boon et al. 2015 "
      "eqs 6-8, Appendix eqs 9-16)";
  static constexpr auto params = power_law_params<ContinuouslyYieldingShear>();
};

/// True for laws that carry a JointStrength (every shear law).
template <class Law>
constexpr bool kHasStrength = requires(const Law& l) {
  l.strength;
};

/// Every key the law takes, in table order (own keys, then strength keys).
template <class Law>
std::vector<std::string_view> law_keys() {
  std::vector<std::string_view> keys;
  for (const auto& p : LawTraits<Law>::params) keys.push_back(p.key);
  if constexpr (kHasStrength<Law>) {
    for (const auto& p : kStrengthParams) keys.push_back(p.key);
  }
  return keys;
}

/// Checks every parameter against its range; the message names `name` and the key.
template <class Law>
void validate_law(const Law& law, std::string_view name = LawTraits<Law>::name) {
  for (const auto& p : LawTraits<Law>::params) {
    check_range(LawTraits<Law>::kind, name, p.key, p.unit, p.range, p.get(law));
  }
  if constexpr (kHasStrength<Law>) law.strength.validate(name);
}

/// A law from named parameters in scenario units; keys not given keep the struct defaults.
/// Throws std::invalid_argument for an unknown key or a value out of range (the value as given).
template <class Law>
Law law_from_params(const std::map<std::string, double>& params) {
  using T = LawTraits<Law>;
  check_known_params(T::kind, T::name, params, law_keys<Law>());
  Law law;
  const auto read = [&](const auto& p, auto& target) {
    const auto it = params.find(std::string(p.key));
    if (it == params.end()) return;
    check_range(T::kind, T::name, p.key, p.unit, p.range, it->second);
    p.set(target, it->second);
  };
  for (const auto& p : T::params) read(p, law);
  if constexpr (kHasStrength<Law>) {
    for (const auto& p : kStrengthParams) read(p, law.strength);
  }
  validate_law(law);
  return law;
}

/// A key and its value in scenario units, as writers print it.
struct LawValue {
  std::string_view key;
  double value;
  std::string_view unit;
};

/// The law's keys and values in table order; optional keys at their default are left out.
template <class Law>
std::vector<LawValue> law_values(const Law& law) {
  std::vector<LawValue> out;
  for (const auto& p : LawTraits<Law>::params) out.push_back({p.key, p.get(law), p.unit});
  if constexpr (kHasStrength<Law>) {
    for (const auto& p : kStrengthParams) {
      if (p.is_default && p.is_default(law.strength)) continue;
      out.push_back({p.key, p.get(law.strength), p.unit});
    }
  }
  return out;
}

/// The keys and values of the law held by a variant.
template <class Variant>
std::vector<LawValue> law_values_of(const Variant& law) {
  return std::visit([](const auto& l) { return law_values(l); }, law);
}

/// "<formula>: key = value unit, ..." (six significant digits), for run reports.
template <class Law>
std::string describe_law(const Law& law) {
  std::ostringstream out;
  out.precision(6);
  out << LawTraits<Law>::formula;
  if constexpr (kHasStrength<Law>) {
    out << ", Mohr-Coulomb tau <= c + sigma_n tan(phi) with tension cut-off sigma_t and "
           "residual phi_r";
  }
  const char* separator = ": ";
  for (const auto& v : law_values(law)) {
    out << separator << v.key << " = " << v.value << " " << v.unit;
    separator = ", ";
  }
  return out.str();
}

/// "a, b, c": the names of the laws of a variant.
template <class Variant>
std::string law_names() {
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    std::string list;
    ((list +=
      (I == 0 ? "" : ", ") + std::string(LawTraits<std::variant_alternative_t<I, Variant>>::name)),
     ...);
    return list;
  }
  (std::make_index_sequence<std::variant_size_v<Variant>>{});
}

/// The alternative of `Variant` whose table is named `name`, built by law_from_params.
/// Throws std::invalid_argument for an unknown name (the message lists the known ones).
template <class Variant>
Variant variant_from_params(std::string_view kind, std::string_view name,
                            const std::map<std::string, double>& params) {
  std::optional<Variant> result;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    static_cast<void>(
        ((name == LawTraits<std::variant_alternative_t<I, Variant>>::name
              ? (result = law_from_params<std::variant_alternative_t<I, Variant>>(params), true)
              : false) ||
         ...));
  }
  (std::make_index_sequence<std::variant_size_v<Variant>>{});
  if (!result) {
    throw std::invalid_argument("unknown " + std::string(kind) + " law '" + std::string(name) +
                                "' (known: " + law_names<Variant>() + ")");
  }
  return *result;
}

}  // namespace blockdem
