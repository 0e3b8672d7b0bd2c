// The contact dashpot (response/contact_damping.hpp) without a world: its coefficient, its cut
// against pulling, the oscillator's mass, and the two halves of its trapezoidal work.
#include "blockdem/response/contact_damping.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "blockdem/geometry/polyhedron.hpp"

namespace blockdem::test::response_contact_damping {
namespace {

// A 1 m cube of 1000 kg/m³ (m = 1000 kg) centred at `centre`.
Block cube(const Eigen::Vector3d& centre, Motion motion = Motion::free) {
  Block b = make_block(Polyhedron::box({1, 1, 1}).transformed(Eigen::Matrix3d::Identity(), centre),
                       1000.0, "cube");
  b.motion = motion;
  return b;
}

// Reference: c = 2 ζ sqrt(m K) with m = m_A m_B / (m_A + m_B) = 500 kg, K = 2e6 N/m, ζ = 0.1:
// c = 2 * 0.1 * sqrt(1e9) = 6324.555 N s/m; closing at 0.01 m/s, F_d = 63.24555 N and the half
// work ½ Δt F_d (v_B - v_A)·n = -½ 1e-3 63.24555 0.01 J. Round-off tolerance (1e-12 relative).
TEST(ContactDashpot, ClosingForceIsTheCriticalFractionTimesTheClosingSpeed) {
  Block a = cube({0, 0, -0.5}), b = cube({0, 0, 0.5});
  b.velocity = {0.0, 0.0, -0.005};
  a.velocity = {0.0, 0.0, 0.005};
  const Eigen::Vector3d x(0, 0, 0), n(0, 0, 1);
  const Dashpot d = contact_dashpot(0.1, a, b, x, n, 2e6, 100.0, 1e-3);
  const double c = 2.0 * 0.1 * std::sqrt(500.0 * 2e6);
  EXPECT_NEAR(d.force, c * 0.01, 1e-12 * c * 0.01);
  EXPECT_NEAR(d.half_work, -0.5 * 1e-3 * c * 0.01 * 0.01, 1e-12 * c * 1e-7);
}

// Against a fixed block the oscillator's mass is the free block's (1000 kg); neither free: none.
TEST(ContactDashpot, MassIsTheFreeBlocksAgainstAFixedOne) {
  EXPECT_DOUBLE_EQ(contact_oscillator_mass(cube({0, 0, 0}, Motion::fixed), cube({0, 0, 1})),
                   1000.0);
  EXPECT_DOUBLE_EQ(contact_oscillator_mass(cube({0, 0, 0}), cube({0, 0, 1})), 500.0);
  EXPECT_EQ(
      contact_oscillator_mass(cube({0, 0, 0}, Motion::fixed), cube({0, 0, 1}, Motion::prescribed)),
      0.0);
}

// Parting fast, the dashpot's pull is cut to the spring's force (total zero), never more; a
// spring in tension (a bonded joint, F_n < 0) gets no pull at all.
TEST(ContactDashpot, DoesNotPullBeyondTheSpring) {
  Block a = cube({0, 0, -0.5}, Motion::fixed), b = cube({0, 0, 0.5});
  b.velocity = {0.0, 0.0, 1.0};
  const Eigen::Vector3d x(0, 0, 0), n(0, 0, 1);
  const Dashpot cut = contact_dashpot(0.2, a, b, x, n, 2e6, 50.0, 1e-3);
  EXPECT_EQ(cut.force, -50.0);
  EXPECT_EQ(cut.half_work, 0.5 * 1e-3 * -50.0 * 1.0);
  EXPECT_EQ(contact_dashpot(0.2, a, b, x, n, 2e6, -30.0, 1e-3).force, 0.0);
  EXPECT_EQ(contact_dashpot(0.0, a, b, x, n, 2e6, 50.0, 1e-3).force, 0.0);
}

// The carried half uses the velocities now and the lever arm about the centre a step before:
// a block spinning at ω about y with its centre moved by dt v. At x = (1, 0, 0) from the old
// centre, (ω × r)·z = -ω; with v = 0 the half is ½ dt F (-ω). Tolerance round-off.
TEST(ContactDashpot, CarriedHalfUsesTheLeverArmOfTheStepBefore) {
  Block a = cube({0, 0, -0.5}, Motion::fixed), b = cube({0, 0, 0.5});
  b.angular_velocity = {0.0, 2.0, 0.0};
  b.velocity = {0.3, 0.0, 0.0};
  const double dt = 1e-3, force = 40.0;
  // The centre now is the old centre (0, 0, 0.5) moved by dt v.
  b.position += dt * b.velocity;
  const Eigen::Vector3d x(1.0, 0.0, 0.0), n(0, 0, 1);
  const double expected =
      0.5 * dt * force * (Eigen::Vector3d(0, 2, 0).cross(x - Eigen::Vector3d(0, 0, 0.5))).z();
  EXPECT_NEAR(dashpot_carried_work(force, a, b, x, n, dt), expected, 1e-15);
}

}  // namespace
}  // namespace blockdem::test::response_contact_damping
