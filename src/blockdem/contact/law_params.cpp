// Error-message and named-parameter helpers for the joint-law factories.
#include "blockdem/contact/law_params.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "blockdem/contact/law_param.hpp"

namespace blockdem {

std::string law_error_prefix(std::string_view kind, std::string_view law) {
  return std::string(kind) + " law '" + std::string(law) + "': ";
}

std::string format_value(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

void check_known_params(std::string_view kind, std::string_view law,
                        const std::map<std::string, double>& params,
                        std::initializer_list<std::string_view> known) {
  check_known_params(kind, law, params, std::vector<std::string_view>(known));
}

void check_known_params(std::string_view kind, std::string_view law,
                        const std::map<std::string, double>& params,
                        const std::vector<std::string_view>& known) {
  for (const auto& [name, value] : params) {
    bool found = false;
    for (const auto k : known) found = found || (k == name);
    if (found) continue;
    std::string list;
    for (const auto k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    throw std::invalid_argument(law_error_prefix(kind, law) + "unknown parameter '" + name +
                                "' (known: " + list + ")");
  }
}

void check_range(std::string_view kind, std::string_view law, std::string_view key,
                 std::string_view unit, ParamRange range, double value) {
  bool ok = false;
  std::string requirement;
  switch (range) {
    case ParamRange::positive:
      ok = std::isfinite(value) && value > 0.0;
      requirement = "a finite positive number (" + std::string(unit) + ")";
      break;
    case ParamRange::non_negative:
      ok = std::isfinite(value) && value >= 0.0;
      requirement = "a finite non-negative number (" + std::string(unit) + ")";
      break;
    case ParamRange::friction_angle:
      ok = std::isfinite(value) && value > 0.0 && value < 90.0;
      requirement = "an angle strictly between 0 and 90 degrees";
      break;
    case ParamRange::stiffness:
      ok = std::isfinite(value) && value >= kMinJointStiffness;
      requirement = "a finite stiffness of at least " + format_value(kMinJointStiffness) + " " +
                    std::string(unit) +
                    " (softer joints' elastic energies overflow; rock joints are 1e6-1e13 Pa/m)";
      break;
  }
  if (!ok) {
    throw std::invalid_argument(law_error_prefix(kind, law) + "parameter '" + std::string(key) +
                                "' must be " + requirement + ", got " + format_value(value));
  }
}

double friction_from_deg(double friction_deg) {
  return std::tan(friction_deg * std::numbers::pi / 180.0);
}

double friction_deg_from(double friction_coefficient) {
  return std::atan(friction_coefficient) * 180.0 / std::numbers::pi;
}

double param_or(const std::map<std::string, double>& params, const std::string& name,
                double fallback) {
  const auto it = params.find(name);
  return it == params.end() ? fallback : it->second;
}

void require_pair(std::string_view kind, std::string_view law,
                  const std::map<std::string, double>& params, const std::string& first,
                  const std::string& second) {
  const bool has_first = params.count(first) > 0;
  const bool has_second = params.count(second) > 0;
  if (has_first != has_second) {
    const std::string& missing = has_first ? second : first;
    const std::string& given = has_first ? first : second;
    throw std::invalid_argument(law_error_prefix(kind, law) + "parameter '" + given + "' needs '" +
                                missing + "' as well");
  }
}

}  // namespace blockdem
