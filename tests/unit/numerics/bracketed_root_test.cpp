// Brent's bracketing root finder: accuracy, speed on smooth functions, robustness on a jump,
// and rejection of a bracket without a sign change.
#include "blockdem/numerics/bracketed_root.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace blockdem {
namespace {

TEST(BracketedRoot, FindsSmoothRootsFast) {
  int evaluations = 0;
  const auto cubic = [&](double x) {
    ++evaluations;
    return x * x * x - 2.0;
  };
  const double root = find_root_bracketed(cubic, 0.0, 2.0, -2.0, 6.0, 1e-14, 0.0);
  EXPECT_NEAR(root, std::cbrt(2.0), 4e-14);
  EXPECT_LT(evaluations, 15);  // bisection alone would need about 47
}

TEST(BracketedRoot, HandlesAFlatFunction) {
  // x^9 - 1e-9: root 0.1, f' = 9e-8 there, and f is nearly flat over most of the bracket.
  const auto f = [](double x) { return std::pow(x, 9) - 1e-9; };
  const double root = find_root_bracketed(f, 0.0, 1.0, f(0.0), f(1.0), 1e-13, 0.0);
  EXPECT_NEAR(root, 0.1, 1e-13);
}

TEST(BracketedRoot, ConvergesOntoAJump) {
  // No root, only a sign change at 0.3: the bracket still shrinks onto it.
  const auto step = [](double x) { return x < 0.3 ? -1.0 : 1.0; };
  const double root = find_root_bracketed(step, 0.0, 1.0, -1.0, 1.0, 1e-12, 0.0);
  EXPECT_NEAR(root, 0.3, 1e-11);
}

TEST(BracketedRoot, ReturnsAnExactEndpointAndRejectsNoSignChange) {
  const auto f = [](double x) { return x - 1.0; };
  EXPECT_EQ(find_root_bracketed(f, 1.0, 3.0, 0.0, 2.0, 1e-12, 0.0), 1.0);
  EXPECT_THROW(find_root_bracketed(f, 2.0, 3.0, 1.0, 2.0, 1e-12, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace blockdem
