// The energy budget (world/energy_budget.hpp) against closed forms: a block dropped on a linear
// joint without damping, a block sliding to rest, a block sliding down an incline, a damped block
// settling, a tumbling block. Each test states its reference and tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scenes.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::energy_budget_test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;
constexpr double kRho = 1207.0;  // (kg/m^3)
constexpr double kKn = 10e9;     // (Pa/m)
constexpr double kKs = 1e9;      // (Pa/m)

class EnergyBudgetTest : public ::testing::TestWithParam<ContactMode> {};

std::string mode_name(const ::testing::TestParamInfo<ContactMode>& p) {
  return to_string(p.param);
}

// A 0.1 m cube dropped from h = 1 mm onto a fixed base, linear normal joint, no damping: the
// joint stays elastic (vertical impact, no slip), so kinetic + elastic = initial + work of
// gravity at every level. Central differences conserve this to round-off while the contact force
// is smooth; the step in which the contact forms adds at most ½ k δ (Δx − δ) <= k (v Δt)² / 8,
// i.e. (Δt/τ)²/4 of the impact energy (τ = sqrt(m / k_n A)). With Δt = τ/50: 1e-4; tolerance
// 2e-4 of m g h over 3 bounces. The gravity work must equal m g times the drop (1e-9 relative).
TEST_P(EnergyBudgetTest, DropOnLinearJointConservesEnergy) {
  WorldSettings s;
  s.contact_mode = GetParam();
  s.gravity = {0, 0, -kG};
  const double a = 0.1, h = 1e-3;
  const double m = kRho * a * a * a;
  const double tau = std::sqrt(m / (kKn * a * a));
  s.time_step = tau / 50.0;
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({0.5, 0.5, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  w.add_block(test::box_block({a, a, a}, {0, 0, a / 2 + h}, kRho));
  const double mgh = m * kG * h;
  double worst = 0.0, max_elastic = 0.0;
  const double period = std::sqrt(2 * h / kG) * 2;  // one bounce of a perfect bounce
  while (w.time() < 3 * period) {
    w.step();
    const EnergyBudget& e = w.energy_budget();
    worst = std::max(worst, std::abs(e.residual()));
    max_elastic = std::max(max_elastic, e.elastic);
    const World::LevelState st = w.level_state(1);
    const double drop = a / 2 + h - st.position.z();
    ASSERT_NEAR(e.gravity_work, m * kG * drop, 1e-9 * mgh + 1e-12);
  }
  EXPECT_GT(max_elastic, 0.9 * mgh) << "the joint must take the impact";
  EXPECT_LT(worst, 2e-4 * mgh);
  // No slip: the joint's dissipation holds only the round-off of the work its forces do that
  // their springs do not hold (response/contact_energy.hpp), 2e-12 of m g h measured.
  EXPECT_LT(std::abs(w.energy_budget().friction_dissipation), 1e-9 * mgh);
  EXPECT_EQ(w.energy_budget().damping_dissipation, 0.0);
}

// A block launched at v0 along a flat fixed base (undamped) slides to rest: all its kinetic
// energy goes into slip, D = ½ m v0² = μ m g d (Coulomb). Tolerance 0.5%, as the distance
// test of the dynamics validation (elastic shear deflection and discretisation far below).
TEST_P(EnergyBudgetTest, SlidingBlockDissipatesItsKineticEnergyByFriction) {
  const double phi = 40.0 * kPi / 180.0;
  const double v0 = 0.5;
  const Eigen::Vector3d size(0.1, 0.1, 0.02);
  WorldSettings s;
  s.contact_mode = GetParam();
  s.gravity = {0, 0, -kG};
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({1.0, 0.3, 0.05}, {0.3, 0, -0.025}, kRho, Motion::fixed, "base"));
  const double m = kRho * size.prod();
  const double closure = m * kG / (kKn * size.x() * size.y());
  Block b = test::box_block(size, {0, 0, size.z() / 2 - closure}, kRho);
  b.velocity = {v0, 0, 0};
  w.add_block(b);
  while (w.blocks()[1].velocity.x() > 0.0) {
    w.step();
    ASSERT_LT(w.time(), 1.0);
  }
  const EnergyBudget& e = w.energy_budget();
  const double ke0 = 0.5 * m * v0 * v0;
  EXPECT_NEAR(e.friction_dissipation, ke0, 5e-3 * ke0);
  const double d = w.blocks()[1].position.x();
  EXPECT_NEAR(e.friction_dissipation, std::tan(phi) * m * kG * d, 5e-3 * ke0);
  EXPECT_LT(std::abs(e.residual()), 1e-3 * ke0);
}

// A flat block released on a base tilted by θ = 55° > φ = 40° (gravity tilted), undamped: it
// slides with a = g (sinθ − cosθ tanφ). Friction dissipates μ m g cosθ per metre of slip, so
// D = tanφ m g cosθ (d − u_e) with u_e = m g sinθ... the elastic shear displacement, which is
// below 1e-6 of d here. Gravity does m g sinθ d. Tolerance 1% (start-up slip, docs/joint-laws.md).
TEST_P(EnergyBudgetTest, InclineSlideDissipatesCoulombWork) {
  const double theta = 55.0 * kPi / 180.0, phi = 40.0 * kPi / 180.0;
  const Eigen::Vector3d size(0.1, 0.1, 0.02);
  WorldSettings s;
  s.contact_mode = GetParam();
  s.gravity = kG * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({1.0, 0.3, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  const double m = kRho * size.prod();
  const double closure = m * kG * std::cos(theta) / (kKn * size.x() * size.y());
  w.add_block(test::box_block(size, {0, 0, size.z() / 2 - closure}, kRho));
  while (w.time() < 0.1) w.step();
  const EnergyBudget& e = w.energy_budget();
  const double d = w.level_state(1).position.x();
  const double coulomb = std::tan(phi) * m * kG * std::cos(theta) * d;
  EXPECT_NEAR(e.friction_dissipation, coulomb, 0.01 * coulomb);
  EXPECT_NEAR(e.gravity_work, m * kG * std::sin(theta) * d, 0.01 * e.gravity_work);
  const double v = w.level_state(1).velocity.x();
  EXPECT_NEAR(e.kinetic, 0.5 * m * v * v, 1e-3 * e.kinetic);
  EXPECT_LT(std::abs(e.residual()), 1e-3 * e.scale());
}

// A block released just above a fixed base with local damping 0.7 settles: at rest the
// kinetic energy is zero, the joint holds ½ W δ with δ = W / (k_n A), gravity has done W (h + δ),
// and the damping took the rest, D = W (h + δ) − ½ W δ. The elastic term is exact for a linear
// law; the budget's error is that of the step in which the contact forms, at most (Δt/τ)²/4 of
// the impact energy W h (see the drop test): with Δt = τ/50, 1e-4; tolerance 2e-4 of W h.
TEST_P(EnergyBudgetTest, DampedSettlingBalancesGravityWorkWithElasticAndDamping) {
  WorldSettings s;
  s.contact_mode = GetParam();
  s.gravity = {0, 0, -kG};
  s.damping = 0.7;
  const double a = 0.1, h = 1e-4;
  s.time_step = std::sqrt(kRho * a * a * a / (kKn * a * a)) / 50.0;
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({0.5, 0.5, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  w.add_block(test::box_block({a, a, a}, {0, 0, a / 2 + h}, kRho));
  const double W = kRho * a * a * a * kG;
  const double delta = W / (kKn * a * a);
  while (w.time() < 0.05) w.step();
  const EnergyBudget& e = w.energy_budget();
  EXPECT_LT(e.kinetic, 1e-9 * W * h);
  EXPECT_NEAR(e.elastic, 0.5 * W * delta, 1e-3 * 0.5 * W * delta);
  EXPECT_NEAR(e.gravity_work, W * (h + delta), 2e-4 * W * h);
  EXPECT_NEAR(e.damping_dissipation, W * (h + delta) - 0.5 * W * delta, 2e-4 * W * h);
  EXPECT_LT(std::abs(e.residual()), 2e-4 * W * h);
}

// A free box tumbling under gravity with no contact: the budget's kinetic energy follows the
// work of gravity (translation exact to round-off) and the rotational part stays constant to
// the integrator's accuracy. Tolerance 1e-6 of the kinetic energy.
TEST_P(EnergyBudgetTest, TumblingBlockBudgetCloses) {
  WorldSettings s;
  s.contact_mode = GetParam();
  s.gravity = {0, 0, -kG};
  s.time_step = 1e-5;
  World w = test::linear_world(kKn, kKs, 40, s);
  Block b = test::box_block({0.3, 0.2, 0.1}, {0, 0, 10}, kRho);
  b.velocity = {0.2, 0, 1};
  b.angular_momentum = b.world_inertia() * Eigen::Vector3d(3, 0.1, 0.2);
  b.angular_velocity = Eigen::Vector3d(3, 0.1, 0.2);
  w.add_block(b);
  w.step();
  const double ke = w.energy_budget().kinetic;
  for (int i = 0; i < 20000; ++i) w.step();
  EXPECT_LT(std::abs(w.energy_budget().residual()), 1e-6 * ke);
}

INSTANTIATE_TEST_SUITE_P(Modes, EnergyBudgetTest,
                         ::testing::Values(ContactMode::boon2012, ContactMode::face_integrated),
                         mode_name);

}  // namespace
}  // namespace blockdem::energy_budget_test
