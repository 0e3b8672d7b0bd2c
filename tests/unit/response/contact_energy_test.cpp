// A contact's side of the energy ledger without a World (response/contact_energy.hpp): the shear
// spring's stored energy and the work it does not hold, along an elastic load and a cap that
// falls at a tiny area; the normal force's unstored work on a uniform closure (a linear spring:
// none).
#include "blockdem/response/contact_energy.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "blockdem/response/shear_response.hpp"

// A namespace of this file's own: the unity build compiles it with files that define helpers of
// the same names.
namespace blockdem::test::response_energy {
namespace {

constexpr double kShear = 1e9;  // k_s (Pa/m)
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

LinearShear law() {
  return LinearShear{kShear, JointStrength::from_friction_deg(40.0)};
}

ShearIncrement increment(const Eigen::Vector3d& du, double force, double area) {
  ShearIncrement inc;
  inc.displacement = du;
  inc.normal_force = force;
  inc.normal_stress = force / area;
  inc.contact_area = area;
  inc.normal = kUp;
  return inc;
}

// Elastic loading from rest at a constant area: the spring holds the work done on it,
// ½ k du² (k = k_s A), and nothing is dissipated (to round-off, 1e-12 of the energy).
TEST(ContactEnergy, ElasticShearLoadIsStoredWhole) {
  const double area = 0.01, du = 1e-7;
  ShearState s;
  const Eigen::Vector3d f0 = s.force;
  const ShearResult r = update_shear(law(), s, increment({du, 0, 0}, 1e4, area));
  const ShearSpringEnergy e = shear_spring_energy(law(), f0, 0.0, s, r, {du, 0, 0});
  const double k = kShear * area;
  EXPECT_NEAR(e.stored, 0.5 * k * du * du, 1e-12 * e.stored);
  EXPECT_LT(std::abs(e.unstored), 1e-12 * e.stored);
}

// A joint that opens: its normal force falls to 1e-3 N and its area to 1e-8 m² (k = 10 N/m) while
// the spring holds 10 N, without slip. Coulomb's cap takes the force to μ F_n; the spring then
// holds ½ |F_1|² / k, and the energy it held at the old stiffness, ½ |F_0|² / k_0, less that, is
// dissipated. The law's own split, dE = F·dF / k at the new k, would release ½ |F_0|² / k = 5 J,
// a million times what the spring held.
TEST(ContactEnergy, ShearForceThatACapRemovesAtATinyAreaDissipatesWhatTheSpringHeld) {
  const double area0 = 0.01, k0 = kShear * area0;
  ShearState s;
  s.force = {10.0, 0, 0};
  s.elastic_energy = 0.5 * 100.0 / k0;
  const double held = s.elastic_energy;
  const Eigen::Vector3d f0 = s.force;
  const ShearResult r = update_shear(law(), s, increment(Eigen::Vector3d::Zero(), 1e-3, 1e-8));
  ASSERT_TRUE(r.sliding);
  EXPECT_LT(s.elastic_energy, -4.9) << "the law's split";
  const ShearSpringEnergy e = shear_spring_energy(law(), f0, held, s, r, Eigen::Vector3d::Zero());
  const double k1 = kShear * 1e-8;
  EXPECT_NEAR(e.stored, 0.5 * s.force.squaredNorm() / k1, 1e-12 * e.stored);
  EXPECT_NEAR(e.unstored, held - e.stored, 1e-12 * held);
  EXPECT_GT(e.unstored, 0.0);
}

// A block pressed straight down on a fixed base over a uniform closure by a linear normal spring
// F = k_n A δ, its closure growing from δ_0 by v Δt in a step: the trapezoidal work done on the
// spring, ½ (F_0 + F_1) v Δt, is ½ k_n A (δ_1² - δ_0²), the change of ½ F δ: nothing unstored
// (to 1e-12 of the energy).
TEST(ContactEnergy, NormalSpringOfAUniformClosureHoldsItsWork) {
  Block base = make_block(Polyhedron::box({1, 1, 0.1}), 2500.0, "base");
  Block cube = make_block(
      Polyhedron::box({0.1, 0.1, 0.1}).transformed(Eigen::Matrix3d::Identity(), {0, 0, 0.1}),
      2500.0, "cube");
  const double v = 0.01, dt = 1e-5, kA = 1e10 * 0.01, d0 = 1e-6, d1 = d0 + v * dt;
  cube.velocity = {0, 0, -v};
  const Eigen::Vector3d x(0, 0, 0.05);
  const NormalLevel last{kA * d0, kUp, x, 0.5 * kA * d0 * d0};
  const NormalLevel now{kA * d1, kUp, x, 0.5 * kA * d1 * d1};
  const double w = normal_unstored_work(base, cube, last, dt, now, dt);
  EXPECT_LT(std::abs(w), 1e-12 * now.energy);
}

}  // namespace
}  // namespace blockdem::test::response_energy
