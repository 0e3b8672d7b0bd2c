// A block on an inclined plane with a cohesive joint (Mohr-Coulomb with cohesion, the limit
// equilibrium of a block on a plane, e.g. Hoek & Bray, Rock Slope Engineering, ch. 7): it holds
// while W sin(psi) <= c A + W cos(psi) tan(phi) and slides once W sin(psi) exceeds it, i.e. above
// psi* = phi + asin(c A cos(phi) / W). Checked 2 % below and 2 % above psi*, in both contact modes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "scenes.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::cohesion_validation_test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;
constexpr double kRho = 1207.0;  // gypsum of the paper's Table 1 (kg/m^3)
constexpr double kKn = 10e9;     // Table 2 (Pa/m)
constexpr double kKs = 1e9;      // Table 2 (Pa/m)

class CohesiveInclineTest : public ::testing::TestWithParam<std::tuple<double, ContactMode>> {};

// A flat block (tipping needs tan(psi) > 5) on a fixed base. Gravity starts normal to the base
// and tilts linearly to psi over 40 ms (about 40 periods of the shear spring, so the shear force
// follows W sin(psi) quasi-statically), with local damping, then holds for 20 ms.
// Below psi*: the bond stays intact and the block rests within twice its elastic shear deflection.
// Above psi*: the bond breaks in shear and the block slides down the plane (more than 100
// elastic deflections, still moving).
TEST_P(CohesiveInclineTest, HoldsBelowLimitEquilibriumAndSlidesAbove) {
  const double ratio = std::get<0>(GetParam());
  const double phi = 30.0 * kPi / 180.0;
  const Eigen::Vector3d size(0.1, 0.1, 0.02);
  const double area = size.x() * size.y();
  const double weight = kRho * size.prod() * kG;
  const double cohesion = 0.5 * weight / area;  // c A = W / 2 (Pa)
  const double psi_limit = phi + std::asin(cohesion * area * std::cos(phi) / weight);
  const double psi = ratio * psi_limit;

  WorldSettings s;
  s.contact_mode = std::get<1>(GetParam());
  s.gravity = kG * Eigen::Vector3d(0, 0, -1);
  s.damping = 0.7;
  World w(s);
  JointLaw law;
  law.name = "cohesive";
  law.normal = LinearNormal{kKn};
  LinearShear shear{kKs, JointStrength::from_friction_deg(30.0)};
  shear.strength.cohesion = cohesion;
  shear.strength.residual_friction_coefficient = std::tan(25.0 * kPi / 180.0);
  law.shear = shear;
  w.add_joint_law(law);
  w.add_joint_rule(JointRule{"", "", 0});
  w.add_block(test::box_block({1.0, 0.3, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  const double closure = weight / (kKn * area);
  w.add_block(test::box_block(size, {0, 0, size.z() / 2 - closure}, kRho));

  const double dt = w.next_time_step();
  const int ramp_steps = static_cast<int>(40e-3 / dt) + 1;
  const int hold_steps = static_cast<int>(20e-3 / dt) + 1;
  for (int i = 1; i <= ramp_steps + hold_steps; ++i) {
    const double angle = psi * std::min(1.0, static_cast<double>(i) / ramp_steps);
    w.settings().gravity = kG * Eigen::Vector3d(std::sin(angle), 0, -std::cos(angle));
    w.step();
  }
  const double elastic = weight * std::sin(psi) / (kKs * area);
  const Block& block = w.blocks()[1];
  if (ratio < 1.0) {
    ASSERT_EQ(w.contact_count(), 1u);
    EXPECT_EQ(w.contacts().front()->shear.bond, BondState::intact);
    EXPECT_EQ(w.broken_bond_count(), 0);
    EXPECT_LT(std::abs(block.position.x()), 2.0 * elastic);
    EXPECT_LT(block.velocity.norm(), 1e-4);
  } else {
    ASSERT_EQ(w.contact_count(), 1u);
    EXPECT_EQ(w.contacts().front()->shear.bond, BondState::broken_in_shear);
    EXPECT_EQ(w.broken_bond_count(), 1) << "one bond, broken once, counted once";
    EXPECT_GT(block.position.x(), 100.0 * elastic);
    EXPECT_GT(block.velocity.x(), 0.0);
  }
  EXPECT_LT(block.rotation_since_start().norm(), 1e-3) << "the flat block must not tip";
}

INSTANTIATE_TEST_SUITE_P(LimitEquilibrium, CohesiveInclineTest,
                         ::testing::Combine(::testing::Values(0.98, 1.02),
                                            ::testing::Values(ContactMode::boon2012,
                                                              ContactMode::face_integrated)),
                         [](const ::testing::TestParamInfo<std::tuple<double, ContactMode>>& p) {
                           return std::string(std::get<0>(p.param) < 1.0 ? "below" : "above") +
                                  "_" + to_string(std::get<1>(p.param));
                         });

}  // namespace
}  // namespace blockdem::cohesion_validation_test
