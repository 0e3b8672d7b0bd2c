// Joint strength (Mohr-Coulomb with tension cut-off and residual friction) driven along
// displacement paths through the kernels: tension to sigma_t then break, shear to
// c + sigma_n tan(phi) then residual, unloading, objectivity, strength reduction, the factory.
#include "blockdem/contact/joint_strength.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <string>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "law_test_support.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::joint_strength_test {
namespace {

using test::invalid_argument_message;

constexpr double kArea = 1.0;      // contact area A_c (m^2)
constexpr double kKs = 1e9;        // shear stiffness (Pa/m)
constexpr double kKn = 1e10;       // normal stiffness (Pa/m)
constexpr double kSigma = 1e6;     // normal stress of the shear paths (Pa)
constexpr double kCohesion = 2e5;  // c (Pa)
constexpr double kTension = 1e5;   // sigma_t (Pa)

double tan_deg(double degrees) {
  return std::tan(degrees * std::numbers::pi / 180.0);
}

/// A linear shear law, phi = 40 deg, phi_r = 30 deg, with c and sigma_t as given.
LinearShear bonded_law(double cohesion, double tension) {
  LinearShear law{kKs, JointStrength::from_friction_deg(40.0)};
  law.strength.cohesion = cohesion;
  law.strength.tensile_strength = tension;
  law.strength.residual_friction_coefficient = tan_deg(30.0);
  return law;
}

ShearIncrement step(const Eigen::Vector3d& du, double sigma,
                    const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
  ShearIncrement inc;
  inc.displacement = du;
  inc.normal_stress = sigma;
  inc.normal_force = sigma * kArea;
  inc.contact_area = kArea;
  inc.normal = normal;
  return inc;
}

TEST(JointStrength, DefaultsCannotBreakAndReduceToPlainMohrCoulomb) {
  const JointStrength s;
  EXPECT_FALSE(s.can_break());
  EXPECT_EQ(s.friction_coefficient, tan_deg(40.0)) << "default phi = 40 deg, bit for bit";
  EXPECT_EQ(s.residual_friction(), s.friction_coefficient);
  // A default law sliding far past its cap and opening stays 'intact' (nothing to break).
  const ShearLaw law = LinearShear{};
  ShearState state;
  for (int i = 0; i < 100; ++i) update_shear(law, state, step({1e-5, 0, 0}, kSigma));
  EXPECT_NEAR(state.force.norm(), kSigma * kArea * tan_deg(40.0), 1e-9 * kSigma);
  update_shear(law, state, step({0, 0, 0}, 0.0));
  EXPECT_EQ(state.bond, BondState::intact);
}

// Tension path: closure from +1e-5 m to -2e-5 m in steps of 1 um, offset by half a step from
// the break. Reference: the linear tension branch
// sigma_n = k_n u_n of an intact joint down to -sigma_t (break at u_n = -sigma_t / k_n = -1e-5 m),
// then an open joint (0). Tolerance: round-off (1e-12 relative).
TEST(JointStrength, TensionUpToTensileStrengthThenBreaksForGood) {
  const NormalLaw normal = LinearNormal{kKn};
  const LinearShear shear = bonded_law(kCohesion, kTension);
  ShearState state;
  const double u_break = -kTension / kKn;
  for (int i = 0; i <= 30; ++i) {
    const double closure = 1e-5 - (i + 0.5) * 1e-6;
    const double sigma = bonded_normal_stress(normal, shear.strength, state, closure);
    if (closure > u_break) {
      EXPECT_NEAR(sigma, kKn * closure, 1e-12 * kTension) << "u_n = " << closure;
      EXPECT_EQ(state.bond, BondState::intact) << "u_n = " << closure;
    } else {
      EXPECT_EQ(sigma, 0.0) << "u_n = " << closure;
      EXPECT_EQ(state.bond, BondState::broken_in_tension) << "u_n = " << closure;
    }
  }
  // Closing again: compression follows the normal law, but tension is gone for good.
  EXPECT_EQ(bonded_normal_stress(normal, shear.strength, state, 2e-6), kKn * 2e-6);
  EXPECT_EQ(bonded_normal_stress(normal, shear.strength, state, -1e-7), 0.0);
  EXPECT_EQ(state.bond, BondState::broken_in_tension);
  // And the shear cap is the residual one, without cohesion: F_n tan(phi_r).
  for (int i = 0; i < 2000; ++i) update_shear(shear, state, step({1e-6, 0, 0}, kSigma));
  EXPECT_NEAR(state.force.norm(), kSigma * kArea * tan_deg(30.0), 1e-9 * kSigma);
}

// The shear kernel sees sigma_n <= -sigma_t directly too: same predicate, same break.
TEST(JointStrength, ShearKernelBreaksAtTheTensionCutOff) {
  const ShearLaw law = bonded_law(kCohesion, kTension);
  ShearState state;
  // Intact in tension, -sigma_t < sigma_n < 0: shear is carried up to c A + F_n tan(phi) > 0.
  const double sigma = -0.5 * kTension;
  const double cap = kCohesion * kArea + sigma * kArea * tan_deg(40.0);
  const ShearResult r = update_shear(law, state, step({-0.5 * cap / kKs, 0, 0}, sigma));
  EXPECT_FALSE(r.broke);
  EXPECT_NEAR(state.force.x(), 0.5 * cap, 1e-9 * cap);
  const ShearResult b = update_shear(law, state, step({0, 0, 0}, -kTension));
  EXPECT_TRUE(b.broke);
  EXPECT_EQ(state.bond, BondState::broken_in_tension);
  EXPECT_EQ(state.force.norm(), 0.0);
}

// Shear path at constant sigma_n = 1 MPa, du = 1 um per step. Reference: elastic F = k_s A u
// while F <= c A + F_n tan(phi) = 1.039 MN; the step that would exceed it breaks the bond and
// ends on the residual cap F_n tan(phi_r); then unloading is elastic (k_s A per step) and
// reversed sliding stops at -F_n tan(phi_r). Tolerance: round-off (1e-9 relative).
TEST(JointStrength, ShearToCohesivePeakThenResidualAndElasticUnloading) {
  const ShearLaw law = bonded_law(kCohesion, kTension);
  const double peak = kCohesion * kArea + kSigma * kArea * tan_deg(40.0);
  const double residual = kSigma * kArea * tan_deg(30.0);
  const double df = kKs * kArea * 1e-6;  // force per step (N)
  ShearState state;
  double largest = 0.0;
  int break_step = -1;
  for (int i = 1; i <= 2000; ++i) {
    const ShearResult r = update_shear(law, state, step({-1e-6, 0, 0}, kSigma));
    largest = std::max(largest, state.force.norm());
    if (r.broke) break_step = i;
    if (break_step < 0) {
      EXPECT_NEAR(state.force.x(), i * df, 1e-9 * peak) << "elastic before the peak, step " << i;
    }
  }
  ASSERT_GT(break_step, 0);
  EXPECT_EQ(break_step, static_cast<int>(std::floor(peak / df)) + 1);
  EXPECT_EQ(state.bond, BondState::broken_in_shear);
  EXPECT_LE(largest, peak * (1 + 1e-12));
  EXPECT_GT(largest, peak - df);
  EXPECT_NEAR(state.force.norm(), residual, 1e-9 * residual);
  // Unloading: elastic, k_s A per step, the bond stays broken.
  for (int i = 1; i <= 100; ++i) {
    update_shear(law, state, step({1e-6, 0, 0}, kSigma));
    EXPECT_NEAR(state.force.x(), residual - i * df, 1e-9 * residual);
  }
  // Reversed sliding on the residual cap (no cohesion any more).
  for (int i = 0; i < 3000; ++i) update_shear(law, state, step({1e-6, 0, 0}, kSigma));
  EXPECT_NEAR(state.force.x(), -residual, 1e-9 * residual);
  EXPECT_EQ(state.bond, BondState::broken_in_shear);
}

// Unloading before the peak leaves the bond intact and returns the force to zero (elastic).
TEST(JointStrength, UnloadingBeforeThePeakIsElasticAndKeepsTheBond) {
  const ShearLaw law = bonded_law(kCohesion, kTension);
  ShearState state;
  for (int i = 0; i < 500; ++i)
    EXPECT_FALSE(update_shear(law, state, step({-1e-6, 0, 0}, kSigma)).broke);
  for (int i = 0; i < 500; ++i) update_shear(law, state, step({1e-6, 0, 0}, kSigma));
  EXPECT_LT(state.force.norm(), 1e-6);
  EXPECT_EQ(state.bond, BondState::intact);
}

// Objectivity: the same path in a rotated frame (normal R e_z, du R du) gives the rotated
// forces and the same break step. Tolerance: 1e-9 relative to the peak.
TEST(JointStrength, ShearPathIsObjective) {
  const ShearLaw law = bonded_law(kCohesion, kTension);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const double peak = kCohesion * kArea + kSigma * kArea * tan_deg(40.0);
  ShearState plain, rotated;
  for (int i = 1; i <= 1500; ++i) {
    const Eigen::Vector3d du(-1e-6 * std::cos(0.001 * i), 0.4e-6, 0);
    const ShearResult a = update_shear(law, plain, step(du, kSigma));
    const ShearResult b = update_shear(
        law, rotated, step(rotation * du, kSigma, rotation * Eigen::Vector3d::UnitZ()));
    EXPECT_EQ(a.broke, b.broke) << "step " << i;
    EXPECT_LT((rotation * plain.force - rotated.force).norm(), 1e-9 * peak) << "step " << i;
  }
  EXPECT_EQ(plain.bond, BondState::broken_in_shear);
  EXPECT_EQ(rotated.bond, plain.bond);
}

// Strength reduction: every strength divided by F, stiffness unchanged; the shear path then
// breaks at (c + sigma_n tan(phi)) / F (same reference and tolerance as the shear path).
TEST(JointStrength, StrengthReductionDividesEveryStrength) {
  const LinearShear law = bonded_law(kCohesion, kTension);
  const double factor = 1.6;
  const ShearLaw reduced = with_reduced_strength(law, factor);
  const auto& r = std::get<LinearShear>(reduced);
  EXPECT_EQ(r.stiffness, law.stiffness);
  EXPECT_DOUBLE_EQ(r.strength.friction_coefficient, tan_deg(40.0) / factor);
  EXPECT_DOUBLE_EQ(r.strength.cohesion, kCohesion / factor);
  EXPECT_DOUBLE_EQ(r.strength.tensile_strength, kTension / factor);
  EXPECT_DOUBLE_EQ(r.strength.residual_friction(), tan_deg(30.0) / factor);
  // A law without a residual angle keeps phi_r = phi after reduction.
  EXPECT_EQ(std::get<LinearShear>(with_reduced_strength(LinearShear{}, 2.0))
                .strength.residual_friction_coefficient.has_value(),
            false);
  const double peak = (kCohesion * kArea + kSigma * kArea * tan_deg(40.0)) / factor;
  ShearState state;
  double largest = 0.0;
  for (int i = 0; i < 1500 && !state.broken(); ++i) {
    update_shear(reduced, state, step({-1e-6, 0, 0}, kSigma));
    if (!state.broken()) largest = state.force.norm();
  }
  EXPECT_TRUE(state.broken());
  EXPECT_LE(largest, peak * (1 + 1e-12));
  EXPECT_GT(largest, peak - kKs * kArea * 1e-6);
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    EXPECT_NE(invalid_argument_message([&] { with_reduced_strength(law, bad); }).find("factor"),
              std::string::npos);
  }
}

// The continuously-yielding law with cohesion: the yield surface at beta = 0 is c A_c, so the
// bond breaks at the first plastic slip, once |F| exceeds c A_c (elastic before, k_s,initial).
TEST(JointStrength, ContinuouslyYieldingBreaksWhenShearExceedsCohesion) {
  ContinuouslyYieldingShear law;
  law.strength.cohesion = 1e4;
  const double k = law.power_laws.initial_stiffness(kSigma) * kArea;
  ShearState state;
  int break_step = -1;
  const double du = 1e-8;
  for (int i = 1; i <= 200 && break_step < 0; ++i) {
    if (update_shear(law, state, step({-du, 0, 0}, kSigma)).broke) break_step = i;
  }
  EXPECT_EQ(break_step, static_cast<int>(std::floor(1e4 * kArea / (k * du))) + 1);
  EXPECT_EQ(state.bond, BondState::broken_in_shear);
}

// A joint can break (a bond to lose) when any one strength beyond friction is there: cohesion
// alone, a tensile strength alone, or a residual friction below the peak alone.
TEST(JointStrength, AnyOneStrengthBeyondFrictionCanBreak) {
  JointStrength cohesive, tensile, softening;
  cohesive.cohesion = 1e5;
  tensile.tensile_strength = 5e4;
  softening.residual_friction_coefficient = tan_deg(25.0);
  EXPECT_TRUE(cohesive.can_break());
  EXPECT_TRUE(tensile.can_break());
  EXPECT_TRUE(softening.can_break());
}

TEST(JointStrength, FactoryReadsStrengthKeysAndRejectsBadOnes) {
  const auto lin =
      std::get<LinearShear>(shear_law_from_params("linear", {{"friction_deg", 35.0},
                                                             {"cohesion", 1e5},
                                                             {"tensile_strength", 5e4},
                                                             {"residual_friction_deg", 25.0}}));
  EXPECT_EQ(lin.strength.friction_coefficient, tan_deg(35.0));
  EXPECT_EQ(lin.strength.cohesion, 1e5);
  EXPECT_EQ(lin.strength.tensile_strength, 5e4);
  EXPECT_EQ(lin.strength.residual_friction(), tan_deg(25.0));
  EXPECT_TRUE(lin.strength.can_break());
  const auto plain = std::get<DegradingShear>(shear_law_from_params("degrading", {}));
  EXPECT_FALSE(plain.strength.can_break());
  EXPECT_EQ(plain.strength.residual_friction(), plain.strength.friction_coefficient);
  const auto message = [](const std::map<std::string, double>& params) {
    return invalid_argument_message([&] { shear_law_from_params("stress_linear", params); });
  };
  EXPECT_NE(message({{"cohesion", -1.0}}).find("'cohesion'"), std::string::npos);
  EXPECT_NE(message({{"tensile_strength", std::nan("")}}).find("'tensile_strength'"),
            std::string::npos);
  EXPECT_NE(message({{"residual_friction_deg", 95.0}}).find("'residual_friction_deg'"),
            std::string::npos);
  const std::string above = message({{"friction_deg", 30.0}, {"residual_friction_deg", 35.0}});
  EXPECT_NE(above.find("shear law 'stress_linear'"), std::string::npos) << above;
  EXPECT_NE(above.find("'residual_friction_deg'"), std::string::npos) << above;
  EXPECT_NE(describe(ShearLaw{lin}).find("cohesion = 100000 Pa"), std::string::npos)
      << describe(ShearLaw{lin});
}

}  // namespace
}  // namespace blockdem::joint_strength_test
