// The critical factor extrapolated from a strength reduction's failed trials
// (world/stability.hpp): a rigid mechanism whose joints have their strength divided by F
// accelerates as a = A - B/F, so two failed trials on the same mechanism give F_c = B/A.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "blockdem/world/stability.hpp"

namespace blockdem::extrapolated_factor_test {
namespace {

StabilityTrial failed(double factor, double acceleration) {
  StabilityTrial t;
  t.parameter = factor;
  t.stable = false;
  t.outcome = TrialOutcome::collapsed;
  t.acceleration = acceleration;
  return t;
}

StabilityTrial stable(double factor) {
  StabilityTrial t;
  t.parameter = factor;
  t.stable = true;
  t.outcome = TrialOutcome::stable;
  return t;
}

// A block on a plane: driving D = W sin(psi), resisting R = W cos(psi) tan(phi), damped by the
// same factor in every trial: a(F) = c (D - R/F) vanishes at F_c = R/D = tan(phi)/tan(psi).
TEST(ExtrapolatedFactor, TwoFailedTrialsOfARigidMechanismGiveItsCriticalFactor) {
  const double d = 0.5, r = 0.7, c = 0.3 * 9.81;  // F_c = 1.4
  const auto a = [&](double f) { return c * (d - r / f); };
  const std::vector<StabilityTrial> trials = {stable(0.5), failed(3.0, a(3.0)), stable(1.75),
                                              failed(2.375, a(2.375))};
  const std::optional<double> fc = extrapolated_factor(trials);
  ASSERT_TRUE(fc.has_value());
  EXPECT_NEAR(*fc, r / d, 1e-12);
}

// The two failed trials of smallest factor are used: a third, far above, whose mechanism is
// another (here a much faster one) does not move the estimate.
TEST(ExtrapolatedFactor, UsesTheTwoFailedTrialsNearestTheStableOnes) {
  const auto a = [](double f) { return 2.0 * (1.0 - 1.2 / f); };  // F_c = 1.2
  const std::vector<StabilityTrial> trials = {failed(4.0, 50.0), failed(1.6, a(1.6)), stable(1.0),
                                              failed(1.3, a(1.3))};
  const std::optional<double> fc = extrapolated_factor(trials);
  ASSERT_TRUE(fc.has_value());
  EXPECT_NEAR(*fc, 1.2, 1e-12);
}

// No estimate: fewer than two failed trials with an acceleration (a diverged trial has none),
// or accelerations that do not grow with F (no rigid mechanism behind them).
TEST(ExtrapolatedFactor, NoneWithoutTwoRisingFailedTrials) {
  EXPECT_FALSE(extrapolated_factor({}).has_value());
  EXPECT_FALSE(extrapolated_factor({stable(1.0), failed(2.0, 0.5)}).has_value());
  EXPECT_FALSE(extrapolated_factor({failed(2.0, 0.5), failed(3.0, 0.0)}).has_value());
  EXPECT_FALSE(extrapolated_factor({failed(2.0, 0.5), failed(3.0, 0.4)}).has_value());
  EXPECT_FALSE(extrapolated_factor({failed(2.0, 0.5), failed(2.0, 0.5)}).has_value());
}

}  // namespace
}  // namespace blockdem::extrapolated_factor_test
