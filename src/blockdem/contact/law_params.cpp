// Error-message and named-parameter helpers for the joint-law factories.
#include "blockdem/contact/law_params.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

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
