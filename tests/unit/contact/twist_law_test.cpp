// The shear law's terms of the torsional spring (twist_law_terms): k_s at σ_n and the friction
// coefficient of the joint's state, against the laws' closed forms (eq 2, eqs 6-8).
#include "blockdem/contact/twist_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace blockdem {
namespace {

// Linear law: k_s and tan φ while intact, tan φ_r once broken (exact).
TEST(TwistLaw, LinearLawUsesPeakThenResidualFriction) {
  JointStrength s = JointStrength::from_friction_deg(40.0);
  s.cohesion = 1e5;
  s.residual_friction_coefficient = std::tan(30.0 * std::acos(-1.0) / 180.0);
  const ShearLaw law = LinearShear{2e9, s};
  ShearState state;
  TwistLawTerms t = twist_law_terms(law, state, 1e5);
  EXPECT_EQ(t.shear_stiffness, 2e9);
  EXPECT_EQ(t.friction_coefficient, s.friction_coefficient);
  state.bond = BondState::broken_in_shear;
  t = twist_law_terms(law, state, 1e5);
  EXPECT_EQ(t.friction_coefficient, s.residual_friction());
}

// Eq 2: k_s = k0 + c σ_n (1e-15 relative).
TEST(TwistLaw, StressLinearStiffnessFollowsEq2) {
  const ShearLaw law = StressLinearShear{1e8, 9.7e4, {}};
  const TwistLawTerms t = twist_law_terms(law, ShearState{}, 5e5);
  EXPECT_NEAR(t.shear_stiffness, 1e8 + 9.7e4 * 5e5, 1e-15 * t.shear_stiffness);
}

// Continuously-yielding law: k_s,initial = A σ_n^B (eq 7) and μ(β) = tan φ (1 - exp(-β/u_peak))
// with u_peak = C σ_n^D (eqs 6, 8): zero for a fresh joint (1e-12 relative).
TEST(TwistLaw, ContinuouslyYieldingFrictionHardensWithPlasticSlip) {
  const ContinuouslyYieldingShear cy;
  const ShearLaw law = cy;
  const double sigma = 5e5;
  ShearState state;
  EXPECT_EQ(twist_law_terms(law, state, sigma).friction_coefficient, 0.0);
  state.plastic_slip = 3e-5;
  const TwistLawTerms t = twist_law_terms(law, state, sigma);
  const double peak = 2e-6 * std::pow(sigma, 0.213);
  const double mu = cy.strength.friction_coefficient * (1.0 - std::exp(-3e-5 / peak));
  EXPECT_NEAR(t.friction_coefficient, mu, 1e-12 * mu);
  EXPECT_NEAR(t.shear_stiffness, 1.9e6 * std::pow(sigma, 0.7), 1e-12 * t.shear_stiffness);
}

}  // namespace
}  // namespace blockdem
