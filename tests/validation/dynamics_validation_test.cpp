// Validation of the dynamics against closed-form answers (issue: engine core, item 7).
// Each test states its reference and tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "blockdem/world/stage.hpp"
#include "scenes.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::dynamics_validation_test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;
constexpr double kRho = 1207.0;  // gypsum of the paper's Table 1 (kg/m^3)
constexpr double kKn = 10e9;     // Table 2 (Pa/m)
constexpr double kKs = 1e9;      // Table 2 (Pa/m)

// Every test runs with both contact modes (point contact and face integration): for these
// scenes (uniform closure over a face, or no contact) both must give the closed form.
class Validation : public ::testing::TestWithParam<ContactMode> {
 protected:
  WorldSettings settings() const {
    WorldSettings s;
    s.contact_mode = GetParam();
    return s;
  }
};

std::string mode_name(const ::testing::TestParamInfo<ContactMode>& p) {
  return to_string(p.param);
}

// Free fall. Central difference integrates constant acceleration exactly when the stored
// velocity is read as v(t - dt/2): x(t_n) = x0 + v(0) t + g t²/2 with v(0) = v_{-1/2} + g dt/2.
// Tolerance: round-off only (1e-12 relative).
TEST_P(Validation, FreeFallIsExactForCentralDifference) {
  WorldSettings s = settings();
  s.gravity = {0, 0, -kG};
  s.time_step = 1e-4;
  World w = test::linear_world(kKn, kKs, 40, s);
  Block b = test::box_block({0.1, 0.1, 0.1}, {0, 0, 1}, kRho);
  b.velocity = {0.3, 0, 1.5};
  w.add_block(b);
  const int n = 1000;
  for (int i = 0; i < n; ++i) w.step();
  const double t = n * s.time_step;
  const Eigen::Vector3d v0 = Eigen::Vector3d(0.3, 0, 1.5) + 0.5 * s.time_step * s.gravity;
  const Eigen::Vector3d expected = Eigen::Vector3d(0, 0, 1) + v0 * t + 0.5 * s.gravity * t * t;
  EXPECT_LT((w.blocks()[0].position - expected).norm(), 1e-12 * expected.norm());
  EXPECT_NEAR(w.time(), t, 1e-12 * t);
}

// A block resting on a fixed base: the joint closes by δ = W / (k_n A) (linear law, full face
// area A). Tolerance 1e-6 relative, set by the equilibrium tolerance of the stage.
TEST_P(Validation, RestingBlockClosureIsWeightOverStiffnessTimesArea) {
  WorldSettings s = settings();
  s.damping = 0.7;
  World w = test::linear_world(kKn, kKs, 40, s);
  const double a = 0.046;
  w.add_block(test::box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  w.add_block(test::box_block({a, a, a}, {0, 0, a / 2}, kRho));
  Stage st;
  st.gravity = Eigen::Vector3d(0, 0, -kG);
  st.unbalanced_tolerance = 1e-9;
  st.kinetic_tolerance = 1e-14;
  const StageResult r = run_stage(w, st);
  ASSERT_TRUE(r.converged) << r.message;
  const double weight = kRho * a * a * a * kG;
  const double closure = weight / (kKn * a * a);
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0]->geometry.overlap, closure, 1e-6 * closure);
  EXPECT_NEAR(contacts[0]->geometry.area, a * a, 1e-12);
  EXPECT_NEAR(contacts[0]->normal_force, weight, 1e-6 * weight);
  EXPECT_NEAR(w.blocks()[1].position.z(), a / 2 - closure, 1e-6 * closure);
}

// Undamped vertical oscillation of a block on a linear joint: period T = 2π sqrt(m / (k_n A)).
// Started at half the static closure at rest, it oscillates about the static closure with
// amplitude half of it and never separates. Leapfrog's period error is O((ω dt)²): with
// ω dt = 0.02 it is below 1e-4; tolerance 5e-4 relative.
TEST_P(Validation, UndampedOscillationPeriod) {
  const double a = 0.046;
  const double m = kRho * a * a * a;
  const double k = kKn * a * a;
  const double period = 2 * kPi * std::sqrt(m / k);
  WorldSettings s = settings();
  s.gravity = {0, 0, -kG};
  s.time_step = 0.02 / std::sqrt(k / m);
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  const double static_closure = m * kG / k;
  w.add_block(test::box_block({a, a, a}, {0, 0, a / 2 - 0.5 * static_closure}, kRho));
  // Upward crossings of the equilibrium height, interpolated linearly.
  const double z_eq = a / 2 - static_closure;
  std::vector<double> crossings;
  double z_prev = w.blocks()[1].position.z(), t_prev = 0.0;
  while (crossings.size() < 6) {
    w.step();
    const double z = w.blocks()[1].position.z();
    if (z_prev < z_eq && z >= z_eq) {
      crossings.push_back(t_prev + (w.time() - t_prev) * (z_eq - z_prev) / (z - z_prev));
    }
    z_prev = z;
    t_prev = w.time();
    ASSERT_LT(w.time(), 20 * period);
    ASSERT_EQ(w.contact_count(), 1u) << "the block must never separate";
  }
  const double measured =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  EXPECT_NEAR(measured, period, 5e-4 * period);
}

// A flat block (tipping needs tan θ > 5) on a fixed base, gravity tilted by θ from the base
// normal. Below the friction angle it sticks: with local damping it comes to rest after moving
// by the elastic shear deflection m g sinθ / (k_s A) (within a factor 2 for the transient) and
// does not creep. Above, undamped, it slides with a = g (sinθ − cosθ tanφ) (Mohr-Coulomb cap);
// tolerance 1% on the acceleration.
class InclineTest : public ::testing::TestWithParam<std::tuple<double, ContactMode>> {};

TEST_P(InclineTest, SticksBelowFrictionAngleSlidesAboveWithCoulombAcceleration) {
  const double theta = std::get<0>(GetParam()) * kPi / 180.0;
  const double phi = 40.0 * kPi / 180.0;
  const Eigen::Vector3d size(0.1, 0.1, 0.02);
  WorldSettings s;
  s.contact_mode = std::get<1>(GetParam());
  s.gravity = kG * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
  if (theta < phi) s.damping = 0.7;
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({1.0, 0.3, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  const double m = kRho * size.prod();
  const double area = size.x() * size.y();
  // Start at the static normal closure, at rest.
  const double closure = m * kG * std::cos(theta) / (kKn * area);
  w.add_block(test::box_block(size, {0, 0, size.z() / 2 - closure}, kRho));
  const double dt = w.next_time_step();
  const int steps_per_ms = static_cast<int>(1e-3 / dt) + 1;
  auto run_ms = [&](double ms) {
    for (int i = 0; i < static_cast<int>(ms * steps_per_ms); ++i) w.step();
  };
  if (theta < phi) {
    run_ms(20);
    const double x20 = w.blocks()[1].position.x();
    run_ms(20);
    const double elastic = m * kG * std::sin(theta) / (kKs * area);
    EXPECT_LT(std::abs(w.blocks()[1].position.x()), 2.0 * elastic);
    EXPECT_LT(std::abs(w.blocks()[1].position.x() - x20), 1e-3 * elastic) << "no creep";
    EXPECT_LT(w.blocks()[1].velocity.norm(), 1e-6);
  } else {
    run_ms(5);  // sliding established
    const double t1 = w.time(), x1 = w.blocks()[1].position.x(), v1 = w.blocks()[1].velocity.x();
    run_ms(20);
    const double t2 = w.time(), v2 = w.blocks()[1].velocity.x();
    const double accel = (v2 - v1) / (t2 - t1);
    const double expected = kG * (std::sin(theta) - std::cos(theta) * std::tan(phi));
    EXPECT_NEAR(accel, expected, 0.01 * expected);
    EXPECT_GT(w.blocks()[1].position.x(), x1);
    EXPECT_LT(w.blocks()[1].rotation_since_start().norm(), 1e-3) << "the flat block must not tip";
  }
}

INSTANTIATE_TEST_SUITE_P(Angles, InclineTest,
                         ::testing::Combine(::testing::Values(20.0, 35.0, 45.0, 55.0),
                                            ::testing::Values(ContactMode::boon2012,
                                                              ContactMode::face_integrated)),
                         [](const ::testing::TestParamInfo<std::tuple<double, ContactMode>>& p) {
                           return std::to_string(static_cast<int>(std::get<0>(p.param))) + "deg_" +
                                  to_string(std::get<1>(p.param));
                         });

// A block launched along a flat fixed base slides to rest after d = v0² / (2 g tanφ).
// Undamped; the elastic shear deflection at rest (μ m g / (k_s A) ~ 1e-7 m) and the step
// discretisation are far below the 0.5% tolerance.
TEST_P(Validation, SlidingBlockStopsAfterCoulombDistance) {
  const double phi = 40.0 * kPi / 180.0;
  const double v0 = 0.5;
  const Eigen::Vector3d size(0.1, 0.1, 0.02);
  WorldSettings s = settings();
  s.gravity = {0, 0, -kG};
  World w = test::linear_world(kKn, kKs, 40, s);
  w.add_block(test::box_block({1.0, 0.3, 0.05}, {0.3, 0, -0.025}, kRho, Motion::fixed, "base"));
  const double m = kRho * size.prod();
  const double closure = m * kG / (kKn * size.x() * size.y());
  Block b = test::box_block(size, {0, 0, size.z() / 2 - closure}, kRho);
  b.velocity = {v0, 0, 0};
  w.add_block(b);
  const double expected = v0 * v0 / (2 * kG * std::tan(phi));
  while (w.blocks()[1].velocity.x() > 0.0) {
    w.step();
    ASSERT_LT(w.time(), 1.0);
  }
  EXPECT_NEAR(w.blocks()[1].position.x(), expected, 5e-3 * expected);
}

// A column of blocks at rest on a fixed base: each joint carries the weight of the blocks above
// it (statics). Tolerance 1e-6 relative, from the stage's equilibrium tolerance.
TEST_P(Validation, ColumnContactForcesEqualWeightAbove) {
  WorldSettings s = settings();
  s.damping = 0.7;
  World w = test::linear_world(kKn, kKs, 40, s);
  const double a = 0.046;
  const int n = 5;
  w.add_block(test::box_block({0.2, 0.2, 0.05}, {0, 0, -0.025}, kRho, Motion::fixed, "base"));
  for (int i = 0; i < n; ++i) w.add_block(test::box_block({a, a, a}, {0, 0, a / 2 + i * a}, kRho));
  Stage st;
  st.gravity = Eigen::Vector3d(0, 0, -kG);
  st.unbalanced_tolerance = 1e-10;
  st.kinetic_tolerance = 1e-16;
  const StageResult r = run_stage(w, st);
  ASSERT_TRUE(r.converged) << r.message;
  const double weight = kRho * a * a * a * kG;
  const auto contacts = w.contacts();
  ASSERT_EQ(contacts.size(), static_cast<std::size_t>(n));
  for (const Contact* c : contacts) {
    // Contact between block c->a and c->b (indices: base 0, blocks 1..n bottom to top).
    const int above = n - c->a;
    EXPECT_NEAR(c->normal_force, above * weight, 1e-6 * above * weight)
        << "joint under block " << c->b;
    EXPECT_LT(c->shear.force.norm(), 1e-9 * weight);
  }
}

// A torque-free tumbling block: the world angular momentum is conserved to round-off (the
// scheme updates L exactly), and the kinetic energy to the integrator's second order: with
// |ω| dt = 1e-3 the drift over 50 turns stays below 1e-5 relative.
TEST_P(Validation, TumblingBlockConservesAngularMomentumAndEnergy) {
  WorldSettings s = settings();
  s.time_step = 1e-4;
  World w = test::linear_world(kKn, kKs, 40, s);
  Block b = test::box_block({0.1, 0.2, 0.3}, {0, 0, 0}, kRho);
  b.angular_velocity = {1.0, 10.0, 0.5};  // near the unstable intermediate axis: it flips
  w.add_block(b);
  const Eigen::Vector3d l0 = w.blocks()[0].angular_momentum;
  const double e0 = w.blocks()[0].kinetic_energy();
  const int steps = static_cast<int>(50 * 2 * kPi / (10.0 * s.time_step));
  double worst = 0.0;
  for (int i = 0; i < steps; ++i) {
    w.step();
    const Block& bb = w.blocks()[0];
    const double e =
        0.5 * bb.angular_momentum.dot(bb.world_inertia().inverse() * bb.angular_momentum);
    worst = std::max(worst, std::abs(e - e0) / e0);
  }
  EXPECT_LT((w.blocks()[0].angular_momentum - l0).norm(), 1e-12 * l0.norm());
  EXPECT_LT(worst, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Modes, Validation,
                         ::testing::Values(ContactMode::boon2012, ContactMode::face_integrated),
                         mode_name);

}  // namespace
}  // namespace blockdem::dynamics_validation_test
