// The twist steps without a World on a square face contact under a uniform closure: the
// torsional spring along a spin path through the bounds it sharpens (advance_twist), and the
// shear force and moment held together against Coulomb's law (limit_shear_and_twist).
#include "blockdem/response/contact_twist.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "blockdem/response/face_twist.hpp"
#include "square_cells.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::response_twist {
namespace {

constexpr double kSide = 0.046;  // square side a (m)
constexpr double kArea = kSide * kSide;
constexpr double kNormal = 1e10;   // k_n (Pa/m)
constexpr double kShear = 1e9;     // k_s (Pa/m)
constexpr double kClosure = 1e-5;  // uniform closure (m): σ_n = 0.1 MPa
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();
const Eigen::Vector3d kCentre(kSide / 2, kSide / 2, 0.0);

// The contact as the world's step sees it: normal response, twist area terms, stress field.
struct SquareContact {
  NormalLaw normal_law = LinearNormal{kNormal};
  LinearShear shear_law{kShear, JointStrength::from_friction_deg(35.0)};
  FaceContactGeometry face = square_cells(kSide, kClosure, 0.0);
  NormalResponse normal = *normal_response(normal_law, ContactGeometry{}, face);
  TwistGeometry geometry = twist_geometry(normal, ContactGeometry{}, face, kUp);
  FaceStress stress() const { return {face.cells, normal_law}; }
  double mu() const { return shear_law.strength.friction_coefficient; }
};

// ∫ r dA of the square about its centre, a³ (√2 + asinh 1) / 6: the pure twist capacity is
// μ σ_n times it, 0.3826 μ F_n a.
double square_radial_moment() {
  return std::pow(kSide, 3) * (std::numbers::sqrt2 + std::asinh(1.0)) / 6.0;
}

// Elastic turning: M = -k_s J θ with J = a⁴/6, the spring k_s J, no slip work; the cheap bound
// certifies every step, so the area terms stay a bound. Reference: the torsional spring of a
// rigid relative rotation (contact/twist.hpp); 1e-12 relative.
TEST(TwistResponse, ElasticTurnOfAFaceIsShearStiffnessTimesPolarMoment) {
  SquareContact c;
  const double j = std::pow(kSide, 4) / 6.0;
  TwistState twist;
  double theta = 0.0;
  for (int i = 0; i < 10; ++i) {
    const TwistStep s = advance_twist(twist, c.shear_law, ShearState{}, c.normal.stress, c.geometry,
                                      c.stress(), 1e-6);
    theta += 1e-6;
    EXPECT_NEAR(s.stiffness, kShear * j, 1e-12 * kShear * j);
    EXPECT_EQ(s.slip_work, 0.0);
  }
  EXPECT_NEAR(twist.moment, -kShear * j * theta, 1e-12 * kShear * j * theta);
  EXPECT_FALSE(c.geometry.exact);
}

// Turning on past the cap: the bounds no longer certify the step, the exact ∫ σ_n r dA is taken
// (and kept in the area terms), and the moment stays at μ σ_n ∫ r dA = 0.3826 μ F_n a (within
// 1e-3: the quadrature about the centre, where r has a kink). A step at the cap dissipates the
// cap times the turn, |M| dθ (1e-9 relative).
TEST(TwistResponse, FullSlipOfAFaceIsTheExactCoulombCap) {
  SquareContact c;
  const double cap = c.mu() * c.normal.stress * square_radial_moment();
  EXPECT_NEAR(cap / (c.mu() * c.normal.force * kSide), 0.3826, 1e-4);
  TwistState twist;
  const double turn = 2e-3;  // rad per step; the cap is reached within 3 steps
  TwistStep s;
  for (int i = 0; i < 6; ++i) {
    s = advance_twist(twist, c.shear_law, ShearState{}, c.normal.stress, c.geometry, c.stress(),
                      turn);
  }
  EXPECT_TRUE(c.geometry.exact);
  EXPECT_NEAR(-twist.moment, cap, 1e-3 * cap);
  EXPECT_NEAR(c.geometry.radial_normal_moment, c.normal.stress * square_radial_moment(),
              1e-3 * c.normal.stress * square_radial_moment());
  EXPECT_NEAR(s.slip_work, -twist.moment * turn, 1e-9 * cap * turn);
}

// A state well inside both limits (0.15 of μ F_n and of the pure-twist cap): the certificate
// suffices and nothing changes, to the bit.
TEST(TwistResponse, LimitLeavesAStateInsideAlone) {
  SquareContact c;
  ShearState shear;
  shear.force = Eigen::Vector3d(0.15 * c.mu() * c.normal.force, 0.0, 0.0);
  TwistState twist{0.15 * c.mu() * c.normal.stress * square_radial_moment()};
  const ShearState before = shear;
  const TwistState twisted = twist;
  ContactMotion motion;
  motion.point = c.normal.shear_point;
  const ShearTwistLimit r = limit_shear_and_twist(
      shear, twist, c.shear_law, c.normal.load(), c.geometry, c.stress(), motion,
      c.normal.force_point, kShear * kArea, kShear * std::pow(kSide, 4) / 6.0);
  EXPECT_FALSE(r.slipped);
  EXPECT_EQ(shear.force, before.force);
  EXPECT_EQ(twist.moment, twisted.moment);
}

// A state at 0.8 of both limits lies outside Coulomb's limit surface (which is inside the box of
// the two limits): it returns to full slip, inside the box, and the springs release energy: the
// drop of F² / (2 k_s A) and M² / (2 k_s J), taken off the shear spring's stored energy.
// References: the limit surface of Coulomb's law at every point (contact/shear_twist.hpp); the
// box to 1e-3 (the quadrature), the energies to 1e-12.
TEST(TwistResponse, LimitReturnsAStateOutsideAndReleasesTheSpringEnergy) {
  SquareContact c;
  const double force_limit = c.mu() * c.normal.force;
  const double moment_limit = c.mu() * c.normal.stress * square_radial_moment();
  const double shear_spring = kShear * kArea, twist_spring = kShear * std::pow(kSide, 4) / 6.0;
  ShearState shear;
  shear.force = Eigen::Vector3d(0.8 * force_limit, 0.0, 0.0);
  shear.elastic_energy = shear.force.squaredNorm() / (2 * shear_spring);
  TwistState twist{0.8 * moment_limit};
  const double f0 = shear.force.squaredNorm(), m0 = twist.moment, e0 = shear.elastic_energy;
  ContactMotion motion;
  motion.point = c.normal.shear_point;
  const ShearTwistLimit r =
      limit_shear_and_twist(shear, twist, c.shear_law, c.normal.load(), c.geometry, c.stress(),
                            motion, c.normal.force_point, shear_spring, twist_spring);
  ASSERT_TRUE(r.slipped);
  EXPECT_LE(shear.force.norm(), force_limit * (1 + 1e-3));
  EXPECT_LE(std::abs(twist.moment), moment_limit * (1 + 1e-3));
  const double shear_released = (f0 - shear.force.squaredNorm()) / (2 * shear_spring);
  const double twist_released = (m0 * m0 - twist.moment * twist.moment) / (2 * twist_spring);
  EXPECT_GT(shear_released + twist_released, 0.0);
  EXPECT_NEAR(r.shear_released, shear_released, 1e-12 * e0);
  EXPECT_NEAR(r.twist_released, twist_released, 1e-12 * m0 * m0 / twist_spring);
  EXPECT_NEAR(shear.elastic_energy, e0 - shear_released, 1e-12 * e0);
}

}  // namespace
}  // namespace blockdem::test::response_twist
