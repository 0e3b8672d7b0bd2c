// The grouted tendon driven without a simulation: a tendon of n elements in fixed rock, its head
// displaced, against the discrete shear-lag system solved by hand for two elements, and an
// elastic-perfectly plastic tendon capped at its yield force.
#include "blockdem/world/bolt.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace blockdem {
namespace bolt_test {
namespace {

// n equal elements of stiffness k, grout springs K at each end of each element (half the
// element's grout), all in fixed rock.
Tendon tendon(int n, double k, double grout, double strength) {
  Tendon t;
  t.u.assign(static_cast<std::size_t>(n) + 1, 0.0);
  for (int e = 0; e < n; ++e) {
    t.elements.push_back({k, 0.0, 0.0});
    t.springs.push_back({e, grout, strength, 0.0, 0.0});
    t.springs.push_back({e + 1, grout, strength, 0.0, 0.0});
  }
  return t;
}

TEST(Tendon, TwoElementsMatchTheHandSolution) {
  // Nodes 0 (plate, u0 = 1e-3), 1 (two springs K), 2 (one spring K): the equilibrium
  //   k (u0 - u1) - k (u1 - u2) - 2 K u1 = 0,  k (u1 - u2) - K u2 = 0.
  const double k = 1e8, kk = 2e7, u0 = 1e-3;
  Tendon t = tendon(2, k, kk, 1e30);
  t.u[0] = u0;
  const std::vector<double> rock(t.springs.size(), 0.0);
  EXPECT_FALSE(t.solve(rock));
  const double u2_over_u1 = k / (k + kk);
  const double u1 = k * u0 / (2 * k + 2 * kk - k * u2_over_u1);
  EXPECT_NEAR(t.u[1], u1, 1e-15);
  EXPECT_NEAR(t.u[2], u2_over_u1 * u1, 1e-15);
  EXPECT_NEAR(t.elements[0].force, k * (u1 - u0), 1e-6);
  // The plate's force balances the grout's on the rock.
  double grout = 0.0;
  for (const auto& s : t.springs) grout += s.force;
  EXPECT_NEAR(t.plate_force() + grout, 0.0, 1e-6);
}

TEST(Tendon, YieldedTendonCarriesItsYieldForce) {
  // The head pulled far: the first element yields at F_y, the grout beyond carries F_y.
  Tendon t = tendon(8, 1e8, 1e9, 1e30);
  t.yield_force = 1e4;
  t.u[0] = -1e-2;  // out of the hole
  const std::vector<double> rock(t.springs.size(), 0.0);
  EXPECT_TRUE(t.solve(rock));
  EXPECT_NEAR(t.elements[0].force, 1e4, 1e-6);
  EXPECT_GT(t.elements[0].plastic, 0.0);
  double grout = 0.0;
  for (const auto& s : t.springs) grout += s.force;
  EXPECT_NEAR(grout, -t.plate_force(), 1e-6);
}

}  // namespace
}  // namespace bolt_test
}  // namespace blockdem
