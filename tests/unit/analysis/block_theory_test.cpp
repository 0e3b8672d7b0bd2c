// Block theory for one block (analysis/block_theory.hpp) against closed forms: a block on an
// inclined plane, F = (W cos(psi) tan(phi) + c A) / (W sin(psi)) (Hoek & Bray, Rock Slope
// Engineering, ch. 7); a block that falls; one that gravity presses into the rock; the bolt
// force of Hoek & Bray's planar failure with reinforcement; and the mode and direction of motion
// against an independent oracle, the nearest admissible direction to gravity found by Dykstra's
// alternating projections onto the half-spaces d . n_i <= 0 (Boyle & Dykstra 1986).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "blockdem/analysis/block_theory.hpp"
#include "blockdem/numerics/units.hpp"

namespace blockdem {
namespace block_theory_test {

const Eigen::Vector3d kDown(0, 0, -9.81);

/// Outward normal of the base of a block resting on a plane dipping psi towards +x: down, into
/// the rock below.
Eigen::Vector3d base_normal(double psi) {
  return {-std::sin(psi), 0.0, -std::cos(psi)};
}

TEST(BlockTheory, BlockOnInclinedPlaneSlidesOnOne) {
  const double psi = deg_to_rad(35.0), phi = deg_to_rad(30.0), weight = 1000.0;
  for (const double cohesion : {0.0, 50.0}) {
    // The base, and two side walls (normals +-y) that it slides along without pressing.
    const std::vector<ContactPlane> planes{
        {base_normal(psi), 2.0, std::tan(phi), cohesion},
        {Eigen::Vector3d::UnitY(), 1.0, std::tan(phi), cohesion},
        {-Eigen::Vector3d::UnitY(), 1.0, std::tan(phi), cohesion}};
    const BlockEquilibrium eq = block_equilibrium(planes, kDown, weight);
    ASSERT_EQ(eq.mode, BlockMode::sliding_one);
    ASSERT_EQ(eq.planes, std::vector<int>{0});
    // Closed form; 1e-12 relative (the same arithmetic in another order).
    const double expected =
        (weight * std::cos(psi) * std::tan(phi) + cohesion * 2.0) / (weight * std::sin(psi));
    EXPECT_NEAR(eq.factor_of_safety, expected, 1e-12 * expected);
    EXPECT_NEAR(eq.normal_force[0], weight * std::cos(psi), 1e-9);
    // Down the dip: +x and down.
    EXPECT_NEAR(eq.direction.x(), std::cos(psi), 1e-12);
    EXPECT_NEAR(eq.direction.z(), -std::sin(psi), 1e-12);
  }
}

TEST(BlockTheory, RoofPrismFalls) {
  // A prism in a roof narrowing downwards: its four sides face up and out, all open as it falls.
  const double t = deg_to_rad(10.0);
  const std::vector<ContactPlane> planes{{{std::cos(t), 0, std::sin(t)}, 1.0, 1.0, 1e4},
                                         {{-std::cos(t), 0, std::sin(t)}, 1.0, 1.0, 1e4},
                                         {{0, std::cos(t), std::sin(t)}, 1.0, 1.0, 1e4},
                                         {{0, -std::cos(t), std::sin(t)}, 1.0, 1.0, 1e4},
                                         {{0, 0, 1}, 1.0, 1.0, 1e4}};
  const BlockEquilibrium eq = block_equilibrium(planes, kDown, 500.0);
  EXPECT_EQ(eq.mode, BlockMode::falling);
  EXPECT_TRUE(eq.planes.empty());
  EXPECT_EQ(eq.factor_of_safety, 0.0);
  EXPECT_NEAR(eq.direction.z(), -1.0, 1e-15);
  // The support that carries 1.5 times the weight, straight up; twice that at 60 degrees off.
  EXPECT_NEAR(support_force(planes, eq, kDown, 500.0, -eq.direction, 1.5), 750.0, 1e-9);
  EXPECT_NEAR(support_force(planes, eq, kDown, 500.0, {std::sin(M_PI / 3), 0, 0.5}, 1.5), 1500.0,
              1e-9);
}

TEST(BlockTheory, FloorBlockIsStable) {
  // A block in a floor: gravity presses it into its base; the sides are vertical.
  const std::vector<ContactPlane> planes{
      {{0, 0, -1}, 1.0, 0.1, 0.0}, {{1, 0, 0}, 1.0, 0.1, 0.0}, {{-1, 0, 0}, 1.0, 0.1, 0.0}};
  EXPECT_EQ(block_equilibrium(planes, kDown, 100.0).mode, BlockMode::stable);
}

TEST(BlockTheory, BoltForceMatchesPlanarFailureWithReinforcement) {
  // Hoek & Bray (ch. 7), a bolt at theta from the up-dip direction towards the plane:
  // F = (c A + (W cos(psi) + T sin(theta)) tan(phi)) / (W sin(psi) - T cos(theta)), solved for T.
  const double psi = deg_to_rad(40.0), phi = deg_to_rad(25.0), w = 2e5, c = 1e3, area = 10.0;
  const Eigen::Vector3d n = base_normal(psi);
  const std::vector<ContactPlane> planes{{n, area, std::tan(phi), c}};
  const BlockEquilibrium eq = block_equilibrium(planes, kDown, w);
  ASSERT_EQ(eq.mode, BlockMode::sliding_one);
  ASSERT_LT(eq.factor_of_safety, 1.0);
  const double required = 1.5;
  for (const double theta_deg : {0.0, 15.0, 25.0, 50.0}) {
    const double theta = deg_to_rad(theta_deg);
    const Eigen::Vector3d bolt = -std::cos(theta) * eq.direction + std::sin(theta) * n;
    const double t = support_force(planes, eq, kDown, w, bolt, required);
    const double expected =
        (w * (required * std::sin(psi) - std::cos(psi) * std::tan(phi)) - c * area) /
        (required * std::cos(theta) + std::sin(theta) * std::tan(phi));
    EXPECT_NEAR(t, expected, 1e-9 * expected) << "theta " << theta_deg;
    // And the factor with that bolt is the one asked for.
    const double f = (c * area + (w * std::cos(psi) + t * std::sin(theta)) * std::tan(phi)) /
                     (w * std::sin(psi) - t * std::cos(theta));
    EXPECT_NEAR(f, required, 1e-9);
  }
  // Already at the factor: no bolt.
  EXPECT_EQ(support_force(planes, eq, kDown, w, -eq.direction, 0.5 * eq.factor_of_safety), 0.0);
}

/// The admissible direction nearest g: Dykstra's projections onto d . n_i <= 0.
Eigen::Vector3d nearest_admissible(const std::vector<ContactPlane>& planes, Eigen::Vector3d g) {
  std::vector<Eigen::Vector3d> correction(planes.size(), Eigen::Vector3d::Zero());
  Eigen::Vector3d x = g;
  for (int sweep = 0; sweep < 20000; ++sweep) {
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const Eigen::Vector3d y = x + correction[i];
      const double over = y.dot(planes[i].normal);
      x = over > 0.0 ? Eigen::Vector3d(y - over * planes[i].normal) : y;
      correction[i] = y - x;
    }
  }
  return x;
}

TEST(BlockTheory, ModeAgreesWithNearestAdmissibleDirection) {
  std::mt19937 rng(20261129);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Vector3d g = kDown.normalized();
  int moving = 0, by_mode[4] = {0, 0, 0, 0};
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<ContactPlane> planes;
    const int count = 1 + trial % 5;
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d n(normal(rng), normal(rng), normal(rng));
      planes.push_back({n.normalized(), 1.0, 0.5, 0.0});
    }
    const BlockEquilibrium eq = block_equilibrium(planes, kDown, 1.0);
    const Eigen::Vector3d s = nearest_admissible(planes, g);
    ++by_mode[static_cast<int>(eq.mode)];
    if (s.norm() < 1e-6) {
      EXPECT_EQ(eq.mode, BlockMode::stable) << "trial " << trial;
      continue;
    }
    ++moving;
    ASSERT_NE(eq.mode, BlockMode::stable) << "trial " << trial;
    // The driving force per unit weight is |s|; the direction s / |s|. Tolerance 1e-6 (the
    // projections' convergence).
    EXPECT_NEAR(eq.driving_force, s.norm(), 1e-6) << "trial " << trial;
    EXPECT_LT((eq.direction - s.normalized()).norm(), 1e-5) << "trial " << trial;
    // The planes it slides on are those s runs along.
    int along = 0;
    for (const ContactPlane& p : planes) along += std::abs(p.normal.dot(s)) < 1e-7 ? 1 : 0;
    EXPECT_EQ(static_cast<int>(eq.planes.size()), along) << "trial " << trial;
  }
  // Every mode occurs among the random blocks.
  EXPECT_GT(moving, 50);
  for (int m = 0; m < 4; ++m) EXPECT_GT(by_mode[m], 10) << to_string(static_cast<BlockMode>(m));
}

}  // namespace block_theory_test
}  // namespace blockdem
