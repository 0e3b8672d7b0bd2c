// Helpers shared by the joint-law factories and validators: error messages naming the law and the
// parameter, and checks of named-parameter maps coming from scenario tables.
#pragma once

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace blockdem {

/// "<kind> law '<law>': ", the start of every joint-law error message (kind: "normal", "shear").
std::string law_error_prefix(std::string_view kind, std::string_view law);

/// A number as it should appear in an error message (shortest round-trip form, "nan", "inf").
std::string format_value(double value);

/// Throws std::invalid_argument if `params` holds a name not in `known`; the message lists the
/// known names.
void check_known_params(std::string_view kind, std::string_view law,
                        const std::map<std::string, double>& params,
                        std::initializer_list<std::string_view> known);
void check_known_params(std::string_view kind, std::string_view law,
                        const std::map<std::string, double>& params,
                        const std::vector<std::string_view>& known);

/// tan(phi) from phi in degrees: the one conversion of a friction angle at the input edge (-).
double friction_from_deg(double friction_deg);
/// phi in degrees from tan(phi), for reports and error messages (degrees).
double friction_deg_from(double friction_coefficient);

/// params[name] if present, else `fallback` (the struct default the documentation announces).
double param_or(const std::map<std::string, double>& params, const std::string& name,
                double fallback);

/// Throws std::invalid_argument unless both or neither of `first` and `second` are present.
void require_pair(std::string_view kind, std::string_view law,
                  const std::map<std::string, double>& params, const std::string& first,
                  const std::string& second);

}  // namespace blockdem
