// Physical and mathematical constants and unit conversions shared by every layer: degrees live
// only at the input and output edges, SI units everywhere inside.
#pragma once

#include <numbers>

namespace blockdem {

inline constexpr double kPi = std::numbers::pi;

/// One g, the unit of gravity levels in inputs and outputs (m/s^2). The voussoir studies and
/// every g_level column use this value (the centrifuge tests were reported in these units).
inline constexpr double kOneG = 9.81;

/// Degrees to radians.
constexpr double deg_to_rad(double degrees) {
  return degrees * (kPi / 180.0);
}
/// Radians to degrees.
constexpr double rad_to_deg(double radians) {
  return radians * (180.0 / kPi);
}

}  // namespace blockdem
