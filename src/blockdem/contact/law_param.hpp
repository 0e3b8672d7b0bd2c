// One named parameter of a joint law as scenario files, lab specs, calibration blocks and reports
// spell it: key, unit, meaning, admissible range, and how to read and write it in a law struct.
#pragma once

#include <string_view>

namespace blockdem {

/// The admissible values of a parameter, in the units scenario files use.
enum class ParamRange {
  positive,        ///< finite and > 0
  non_negative,    ///< finite and >= 0
  friction_angle,  ///< an angle strictly between 0 and 90 degrees
  /// A joint stiffness (Pa/m): finite and at least kMinJointStiffness.
  stiffness,
};

/// The softest joint stiffness a law takes (Pa/m): a metre of closure or slip per pascal, far
/// below any rock joint (1e6-1e13 Pa/m). Softer joints' elastic energies sigma^2 / (2 k) A
/// overflow a double at joint stresses, and their displacements are not small.
inline constexpr double kMinJointStiffness = 1.0;

/// A parameter of a law struct `Law`. `get` and `set` work in the units of `unit` (degrees for
/// angles, which the struct stores as tangents).
template <class Law>
struct LawParam {
  std::string_view key;      ///< scenario key, e.g. "friction_deg"
  std::string_view unit;     ///< e.g. "Pa/m", "deg", "-"
  std::string_view meaning;  ///< one phrase for docs and reports
  ParamRange range;
  double (*get)(const Law&);
  void (*set)(Law&, double);
  bool strength = false;  ///< a strength, divided by the factor of a strength reduction
  /// Non-null for an optional key: true when the law holds the value the key's absence gives,
  /// and writers then leave the key out.
  bool (*is_default)(const Law&) = nullptr;
};

/// Throws std::invalid_argument "<kind> law '<law>': parameter '<key>' must be ..., got <value>"
/// unless `value` lies in `range`.
void check_range(std::string_view kind, std::string_view law, std::string_view key,
                 std::string_view unit, ParamRange range, double value);

}  // namespace blockdem
