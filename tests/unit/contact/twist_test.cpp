// The torsional spring driven along prescribed spin paths: elastic moment k_s J θ for a square
// contact (J = a⁴/6), the Coulomb cap μ σ_n ∫ r dA at full slip, elastic unloading after slip, and
// objectivity of the relative spin.
#include "blockdem/contact/twist.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::twist_test {
namespace {

constexpr double kSide = 0.046;  // a (m)
constexpr double kShear = 1e9;   // k_s (Pa/m), the paper's Table 2
constexpr double kStress = 1e5;  // σ_n (Pa)
const double kMu = std::tan(40.0 * 3.14159265358979323846 / 180.0);
const double kJ = std::pow(kSide, 4) / 6.0;                                            // m^4
const double kRadial = std::pow(kSide, 3) * (std::sqrt(2.0) + std::asinh(1.0)) / 6.0;  // m^3

TwistIncrement step(double spin) {
  TwistIncrement inc;
  inc.spin = spin;
  inc.shear_stiffness = kShear;
  inc.polar_moment = kJ;
  inc.radial_normal_moment = kStress * kRadial;
  inc.friction_coefficient = kMu;
  return inc;
}

TEST(Twist, ElasticMomentIsShearStiffnessTimesPolarMoment) {
  // Reference: M = -k_s J θ (moment on B against its spin), within 1%. θ in 100 steps, below slip.
  const double theta = 1e-6;
  TwistState s;
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(update_twist(s, step(theta / 100)).sliding);
  EXPECT_NEAR(s.moment / (-kShear * kJ * theta), 1.0, 1e-2);
}

TEST(Twist, FullSlipMomentIsTheCoulombCap) {
  // Reference: |M| = μ σ_n ∫ r dA over the square at full slip, within 2%. Slip starts at
  // θ = μ σ_n ∫ r dA / (k_s J) = 4.2e-3 rad; twist to 1e-2 rad.
  TwistState s;
  TwistResult r;
  for (int i = 0; i < 100; ++i) r = update_twist(s, step(1e-4));
  EXPECT_TRUE(r.sliding);
  EXPECT_NEAR(-s.moment / (kMu * kStress * kRadial), 1.0, 2e-2);
}

TEST(Twist, UnloadsElasticallyAfterSlip) {
  // After slipping, a reversed spin dθ changes M by +k_s J dθ exactly (no slip while below cap).
  TwistState s;
  TwistResult loading;
  for (int i = 0; i < 50; ++i) loading = update_twist(s, step(1e-4));
  ASSERT_TRUE(loading.sliding);
  const double at_cap = s.moment;
  const TwistResult r = update_twist(s, step(-1e-7));
  EXPECT_FALSE(r.sliding);
  EXPECT_NEAR(s.moment - at_cap, kShear * kJ * 1e-7, 1e-9 * std::abs(at_cap));
}

TEST(Twist, NoSpinNoMoment) {
  TwistState s;
  for (int i = 0; i < 10; ++i) update_twist(s, step(0.0));
  EXPECT_EQ(s.moment, 0.0);
}

TEST(Twist, RigidRotationOfBothBlocksGivesNoSpin) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d omega(gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Vector3d n = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    EXPECT_EQ(relative_spin(omega, omega, n, 1e-5), 0.0);
    // Spin of B alone about n is seen in full.
    EXPECT_NEAR(relative_spin(omega, omega + 2.0 * n, n, 1e-5), 2e-5, 1e-18);
  }
}

TEST(Twist, RejectsBadInput) {
  TwistState s;
  TwistIncrement bad = step(1e-6);
  bad.polar_moment = -1.0;
  EXPECT_THROW(update_twist(s, bad), std::invalid_argument);
  bad = step(std::nan(""));
  EXPECT_THROW(update_twist(s, bad), std::invalid_argument);
}

}  // namespace
}  // namespace blockdem::twist_test
