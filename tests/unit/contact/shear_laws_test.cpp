// Shear laws with a Mohr-Coulomb cap (linear, stress-linear eq 2, degrading eqs 5-7) driven along
// prescribed displacement paths, plus validation, factories and the time-step stiffness estimate.
#include "blockdem/contact/shear_laws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "law_test_support.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::shear_laws_test {
namespace {

using test::invalid_argument_message;
using test::relative_difference;

/// A face of the paper's 46 mm blocks at the full beam's 0.5 MPa.
constexpr double kArea = 0.046 * 0.046;  // m^2
constexpr double kStress = 0.5e6;        // Pa
const double kTan40 = std::tan(40.0 * std::numbers::pi / 180.0);

ShearIncrement step_along(const Eigen::Vector3d& du, double stress = kStress, double area = kArea) {
  ShearIncrement inc;
  inc.displacement = du;
  inc.normal_stress = stress;
  inc.contact_area = area;
  inc.normal_force = stress * area;
  inc.normal = Eigen::Vector3d::UnitZ();
  return inc;
}

TEST(LinearShear, ElasticUntilTheCapThenSlidesAtExactlyFnTanPhi) {
  const LinearShear law{1e9, JointStrength::from_friction_deg(40.0)};
  const double stiffness = law.stiffness * kArea;  // N/m
  const double cap = kStress * kArea * kTan40;     // N
  const double du = 1e-6;
  ShearState state;
  double u = 0.0, slip = 0.0;
  bool reached = false;
  for (int i = 0; i < 600; ++i) {
    const ShearResult r = update_shear(law, state, step_along(Eigen::Vector3d(du, 0, 0)));
    u += du;
    if (stiffness * u <= cap) {
      // Still elastic: F = -k A u on B, opposing the relative displacement.
      EXPECT_FALSE(r.sliding);
      EXPECT_LT(relative_difference(state.force.x(), -stiffness * u), 1e-12);
    } else {
      reached = true;
      EXPECT_TRUE(r.sliding);
      EXPECT_LT(relative_difference(state.force.norm(), cap), 1e-15);
      EXPECT_LT(state.force.x(), 0.0);
      slip = u - cap / stiffness;
      EXPECT_LT(relative_difference(state.plastic_slip, slip), 1e-9);
    }
    EXPECT_EQ(state.force.y(), 0.0);
    EXPECT_EQ(state.force.z(), 0.0);
  }
  ASSERT_TRUE(reached);
  // Once sliding, every step is all slip and dissipates cap * du.
  const ShearResult r = update_shear(law, state, step_along(Eigen::Vector3d(du, 0, 0)));
  EXPECT_LT(relative_difference(r.slip_increment, du), 1e-9);
  EXPECT_LT(relative_difference(r.plastic_work, cap * du), 1e-9);
}

TEST(LinearShear, ReversalUnloadsElasticallyAndSlidesBackAtTheCap) {
  const LinearShear law{1e9, JointStrength::from_friction_deg(30.0)};
  const double stiffness = law.stiffness * kArea;
  const double cap = kStress * kArea * std::tan(30.0 * std::numbers::pi / 180.0);
  ShearState state;
  update_shear(law, state, step_along(Eigen::Vector3d(3.0 * cap / stiffness, 0, 0)));
  ASSERT_DOUBLE_EQ(state.force.x(), -cap);
  // Back by cap / k: elastic, the force drops by k A du, to zero.
  const ShearResult back =
      update_shear(law, state, step_along(Eigen::Vector3d(-cap / stiffness, 0, 0)));
  EXPECT_FALSE(back.sliding);
  EXPECT_NEAR(state.force.x(), 0.0, 1e-9 * cap);
  const ShearResult further =
      update_shear(law, state, step_along(Eigen::Vector3d(-5.0 * cap / stiffness, 0, 0)));
  EXPECT_TRUE(further.sliding);
  EXPECT_LT(relative_difference(state.force.x(), cap), 1e-14);
}

TEST(LinearShear, OpenJointCarriesNoShear) {
  const LinearShear law;
  ShearState state;
  update_shear(law, state, step_along(Eigen::Vector3d(1e-6, 0, 0)));
  ASSERT_GT(state.force.norm(), 0.0);
  const double slip_before = state.plastic_slip;
  const ShearResult r = update_shear(law, state, step_along(Eigen::Vector3d(1e-6, 0, 0), 0.0));
  EXPECT_EQ(state.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(state.plastic_slip, slip_before);
  EXPECT_FALSE(r.sliding);
}

TEST(StressLinearShear, StiffnessIsEq2) {
  const StressLinearShear law;  // eq 2: 1e8 + 9.7e4 sigma_n
  for (const double stress : {1e4, 0.5e6, 1e6}) {
    ShearState state;
    const double du = 1e-7;
    const ShearResult r = update_shear(law, state, step_along(Eigen::Vector3d(0, du, 0), stress));
    const double expected = (1e8 + 9.7e4 * stress) * kArea;
    EXPECT_LT(relative_difference(r.stiffness, expected), 1e-15);
    EXPECT_LT(relative_difference(state.force.y(), -expected * du), 1e-15);
    EXPECT_DOUBLE_EQ(shear_stiffness_estimate(law, stress), 1e8 + 9.7e4 * stress);
  }
}

TEST(DegradingShear, StiffnessFallsLinearlyToZeroAtPeakDisplacement) {
  // At 0.5 MPa eq 5 peaks at tau = k_s,initial u_peak / 2 = 0.36 MPa, below sigma tan 40 = 0.42
  // MPa, so the Mohr-Coulomb cap stays inactive.
  const DegradingShear law;
  const double initial = law.power_laws.initial_stiffness(kStress);  // Pa/m
  const double peak = law.power_laws.peak_displacement(kStress);     // m
  EXPECT_LT(relative_difference(initial, 1.9e6 * std::pow(kStress, 0.7)), 1e-15);
  EXPECT_LT(relative_difference(peak, 2e-6 * std::pow(kStress, 0.213)), 1e-15);
  ASSERT_LT(0.5 * initial * peak, kStress * kTan40);
  const int steps = 157;  // the step that crosses u_peak is split inside
  const double du = 1.3 * peak / steps;
  ShearState state;
  double u = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double before = state.force.x();
    const ShearResult r = update_shear(law, state, step_along(Eigen::Vector3d(du, 0, 0)));
    const double tangent = (state.force.x() - before) / (-kArea * du);
    // Exact mean of k_s over the step: the integral of eq 5 from u to u + du.
    const double lo = std::min(u, peak), hi = std::min(u + du, peak);
    const double expected = initial * ((hi - lo) - (hi * hi - lo * lo) / (2.0 * peak)) / du;
    EXPECT_NEAR(tangent, expected, 1e-9 * initial) << "u / u_peak = " << u / peak;
    EXPECT_LT(relative_difference(r.stiffness, expected * kArea), 1e-9);
    EXPECT_FALSE(r.sliding);
    u += du;
  }
  // The force reached the peak of the integrated eq 5 and stopped there.
  EXPECT_LT(relative_difference(-state.force.x(), 0.5 * initial * peak * kArea), 1e-12);
  EXPECT_LT(relative_difference(state.elastic_displacement.norm(), peak), 1e-15);
  EXPECT_LT(relative_difference(state.plastic_slip, u - peak), 1e-9);
  // Back to the start: unloading retraces the loading curve to zero force.
  for (int i = 0; i < 10; ++i)
    update_shear(law, state, step_along(Eigen::Vector3d(-peak / 10, 0, 0)));
  EXPECT_NEAR(state.force.x(), 0.0, 1e-12 * initial * peak * kArea);
}

TEST(DegradingShear, MohrCoulombCapAtLowNormalStress) {
  // At 1 kPa eq 5 would peak above sigma tan 40: the cap acts first and U_e stops growing.
  const DegradingShear law;
  const double stress = 1e3;
  const double peak = law.power_laws.peak_displacement(stress);
  ASSERT_GT(0.5 * law.power_laws.initial_stiffness(stress) * peak, stress * kTan40);
  ShearState state;
  bool slid = false;
  double held = 0.0;
  for (int i = 0; i < 200; ++i) {
    const ShearResult r =
        update_shear(law, state, step_along(Eigen::Vector3d(peak / 100, 0, 0), stress));
    if (r.sliding) {
      if (slid) {
        EXPECT_DOUBLE_EQ(state.elastic_displacement.x(), held);
      }
      slid = true;
      held = state.elastic_displacement.x();
      EXPECT_LT(relative_difference(state.force.norm(), stress * kArea * kTan40), 1e-14);
    }
  }
  EXPECT_TRUE(slid);
  EXPECT_LT(held, peak);
}

TEST(ShearLaws, StiffnessEstimates) {
  EXPECT_EQ(shear_stiffness_estimate(LinearShear{2e9, JointStrength::from_friction_deg(40.0)}, 1e6),
            2e9);
  const ContinuouslyYieldingShear cy;
  EXPECT_DOUBLE_EQ(shear_stiffness_estimate(cy, 1e6), 1.9e6 * std::pow(1e6, 0.7));
  EXPECT_EQ(shear_stiffness_estimate(cy, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(shear_stiffness_estimate(DegradingShear{}, 2e4), 1.9e6 * std::pow(2e4, 0.7));
}

TEST(ShearLaws, TangentialPartOfTheIncrementOnly) {
  // A component of du along the normal is not shear.
  const LinearShear law;
  ShearState a, b;
  update_shear(law, a, step_along(Eigen::Vector3d(1e-6, -2e-6, 0)));
  update_shear(law, b, step_along(Eigen::Vector3d(1e-6, -2e-6, 5e-6)));
  EXPECT_EQ(a.force, b.force);
}

TEST(ShearLaws, RejectsBadIncrements) {
  const LinearShear law;
  ShearState state;
  auto inc = step_along(Eigen::Vector3d(1e-6, 0, 0));
  inc.contact_area = 0.0;
  EXPECT_NE(invalid_argument_message([&] { update_shear(law, state, inc); }).find("contact_area"),
            std::string::npos);
  inc = step_along(Eigen::Vector3d(std::nan(""), 0, 0));
  EXPECT_NE(invalid_argument_message([&] { update_shear(law, state, inc); }).find("displacement"),
            std::string::npos);
  inc = step_along(Eigen::Vector3d(1e-6, 0, 0));
  inc.normal = Eigen::Vector3d(0, 0, 2);
  EXPECT_NE(invalid_argument_message([&] { update_shear(law, state, inc); }).find("unit"),
            std::string::npos);
}

/// Asserts that validating `law` fails with a message naming the law and the parameter.
void expect_rejected(const ShearLaw& law, const std::string& name, const std::string& parameter) {
  const std::string message = invalid_argument_message([&] { validate(law); });
  EXPECT_NE(message.find("shear law '" + name + "'"), std::string::npos) << message;
  EXPECT_NE(message.find("'" + parameter + "'"), std::string::npos) << message;
}

TEST(ShearLaws, ValidationNamesLawAndParameter) {
  expect_rejected(LinearShear{-1e9, JointStrength::from_friction_deg(40.0)}, "linear", "stiffness");
  for (const double angle : {0.0, 90.0, -10.0, 120.0, std::nan("")}) {
    expect_rejected(LinearShear{1e9, JointStrength::from_friction_deg(angle)}, "linear",
                    "friction_deg");
    expect_rejected(ContinuouslyYieldingShear{{}, JointStrength::from_friction_deg(angle)},
                    "continuously_yielding", "friction_deg");
  }
  expect_rejected(StressLinearShear{-1.0, 9.7e4, JointStrength::from_friction_deg(40.0)},
                  "stress_linear", "k0");
  expect_rejected(StressLinearShear{1e8, -9.7e4, JointStrength::from_friction_deg(40.0)},
                  "stress_linear", "c");
  ShearPowerLaws p;
  p.peak_coefficient = 0.0;  // u_peak = 0
  expect_rejected(DegradingShear{p, JointStrength::from_friction_deg(40.0)}, "degrading",
                  "peak_coefficient");
  expect_rejected(ContinuouslyYieldingShear{p, JointStrength::from_friction_deg(40.0)},
                  "continuously_yielding", "peak_coefficient");
  p = ShearPowerLaws{};
  p.stiffness_coefficient = -1.9e6;
  expect_rejected(ContinuouslyYieldingShear{p, JointStrength::from_friction_deg(40.0)},
                  "continuously_yielding", "stiffness_coefficient");
  p = ShearPowerLaws{};
  p.stiffness_exponent = std::nan("");
  expect_rejected(DegradingShear{p, JointStrength::from_friction_deg(40.0)}, "degrading",
                  "stiffness_exponent");
  p = ShearPowerLaws{};
  p.peak_exponent = -0.2;
  expect_rejected(DegradingShear{p, JointStrength::from_friction_deg(40.0)}, "degrading",
                  "peak_exponent");
  for (const ShearLaw& law : {ShearLaw{LinearShear{}}, ShearLaw{StressLinearShear{}},
                              ShearLaw{DegradingShear{}}, ShearLaw{ContinuouslyYieldingShear{}}}) {
    EXPECT_NO_THROW(validate(law)) << law_name(law);
  }
}

TEST(ShearLaws, FactoryReadsNamedParameters) {
  const auto cy = std::get<ContinuouslyYieldingShear>(
      shear_law_from_params("continuously_yielding", {{"friction_deg", 35.0}}));
  EXPECT_EQ(cy.strength.friction_coefficient, std::tan(35.0 * std::numbers::pi / 180.0));
  EXPECT_EQ(cy.power_laws.stiffness_coefficient, 1.9e6);
  EXPECT_EQ(cy.power_laws.stiffness_exponent, 0.7);
  EXPECT_EQ(cy.power_laws.peak_coefficient, 2e-6);
  EXPECT_EQ(cy.power_laws.peak_exponent, 0.213);
  const auto deg = std::get<DegradingShear>(shear_law_from_params(
      "degrading", {{"peak_coefficient", 3e-6}, {"stiffness_exponent", 0.6}}));
  EXPECT_EQ(deg.power_laws.peak_coefficient, 3e-6);
  EXPECT_EQ(deg.power_laws.stiffness_exponent, 0.6);
  const auto sl = std::get<StressLinearShear>(shear_law_from_params("stress_linear", {}));
  EXPECT_EQ(sl.k0, 1e8);
  EXPECT_EQ(sl.c, 9.7e4);
  const auto lin = std::get<LinearShear>(shear_law_from_params("linear", {{"stiffness", 2e9}}));
  EXPECT_EQ(lin.stiffness, 2e9);
  EXPECT_EQ(lin.strength.friction_coefficient, std::tan(40.0 * std::numbers::pi / 180.0));
  for (const std::string name : {"linear", "stress_linear", "degrading", "continuously_yielding"}) {
    EXPECT_EQ(law_name(shear_law_from_params(name, {})), name);
    EXPECT_FALSE(describe(shear_law_from_params(name, {})).empty());
  }
}

TEST(ShearLaws, FactoryRejectsWhatItCannotRead) {
  const auto unknown = invalid_argument_message([] {
    shear_law_from_params("continuously_yielding", {{"mu0", 0.8}});
  });
  EXPECT_NE(unknown.find("shear law 'continuously_yielding'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("unknown parameter 'mu0'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("friction_deg"), std::string::npos) << unknown;
  EXPECT_NE(invalid_argument_message([] {
              shear_law_from_params("linear", {{"k0", 1e8}});
            }).find("'k0'"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] { shear_law_from_params("barton", {}); }).find("'barton'"),
            std::string::npos);
  EXPECT_NE(invalid_argument_message([] {
              shear_law_from_params("linear", {{"friction_deg", 95.0}});
            }).find("'friction_deg'"),
            std::string::npos);
}

}  // namespace
}  // namespace blockdem::shear_laws_test
