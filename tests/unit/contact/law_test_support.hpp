// Test support for the contact-law tests: a slow, obviously-correct quadrature oracle and
// helpers to compare numbers and catch error messages.
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace blockdem::test {

/// Composite 5-point Gauss-Legendre rule on `pieces` equal subintervals of [lo, hi]; exact for
/// polynomials of degree 9 on each piece.
template <class Function>
double gauss_legendre(Function&& f, double lo, double hi, int pieces) {
  static constexpr std::array<double, 5> nodes = {0.0, -0.5384693101056831, 0.5384693101056831,
                                                  -0.9061798459386640, 0.9061798459386640};
  static constexpr std::array<double, 5> weights = {0.5688888888888889, 0.4786286704993665,
                                                    0.4786286704993665, 0.2369268850561891,
                                                    0.2369268850561891};
  const double h = (hi - lo) / pieces;
  double sum = 0.0;
  for (int p = 0; p < pieces; ++p) {
    const double mid = lo + (p + 0.5) * h;
    for (int i = 0; i < 5; ++i) sum += weights[i] * f(mid + 0.5 * h * nodes[i]);
  }
  return 0.5 * h * sum;
}

/// Relative difference |a - b| / |b| (or |a| when b = 0).
inline double relative_difference(double a, double b) {
  return b == 0.0 ? std::abs(a) : std::abs(a - b) / std::abs(b);
}

/// The message of the std::invalid_argument thrown by f, or "" if none is thrown.
template <class Function>
std::string invalid_argument_message(Function&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace blockdem::test
