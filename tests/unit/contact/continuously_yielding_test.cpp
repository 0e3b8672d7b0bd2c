// The continuously-yielding shear law (Boon, Houlsby & Utili 2015, eq 8 and Appendix eqs 9-16)
// driven along displacement paths: yield condition, exact monotonic solution, convergence under
// step halving, elastic unloading, isotropic hardening, open joints.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "blockdem/contact/shear_laws.hpp"
#include "law_test_support.hpp"

namespace blockdem {
namespace {

using test::relative_difference;

constexpr double kArea = 0.046 * 0.046;  // m^2, a face of the paper's full blocks
constexpr double kStress = 0.5e6;        // Pa, the full beam's joint stress
const double kMu0 = std::tan(40.0 * std::numbers::pi / 180.0);

ShearIncrement step_along(const Eigen::Vector3d& du, double stress = kStress) {
  ShearIncrement inc;
  inc.displacement = du;
  inc.normal_stress = stress;
  inc.contact_area = kArea;
  inc.normal_force = stress * kArea;
  inc.normal = Eigen::Vector3d::UnitZ();
  return inc;
}

struct Fixture {
  ContinuouslyYieldingShear law;
  double peak = law.power_laws.peak_displacement(kStress);               // u_peak (m)
  double stiffness = law.power_laws.initial_stiffness(kStress) * kArea;  // k_s A (N/m)
  double normal_force = kStress * kArea;                                 // F_n (N)

  double mu(double beta) const { return -kMu0 * std::expm1(-beta / peak); }
  /// |F| on the yield surface at plastic slip beta (N).
  double yield_force(double beta) const { return mu(beta) * normal_force; }
};

/// Exact solution of monotonic loading in a fixed direction: every increment is plastic from the
/// start (mu(0) = 0), |F| = mu(beta) F_n and du = dbeta + d|F| / k, so u = beta + mu(beta) F_n / k.
/// Returns |F| at total displacement u, by bisection on beta in [0, u].
double exact_monotonic_force(const Fixture& f, double u) {
  double lo = 0.0, hi = u;
  for (int i = 0; i < 200; ++i) {
    const double beta = 0.5 * (lo + hi);
    (beta + f.yield_force(beta) / f.stiffness < u ? lo : hi) = beta;
  }
  return f.yield_force(0.5 * (lo + hi));
}

TEST(ContinuouslyYielding, NoStrengthAtZeroSlip) {
  // mu(0) = 0: the very first increment, however small, is plastic.
  const Fixture f;
  for (const double du : {1e-12, 1e-9, 1e-6}) {
    ShearState state;
    const ShearResult r = update_shear(f.law, state, step_along(Eigen::Vector3d(du, 0, 0)));
    EXPECT_TRUE(r.sliding) << du;
    EXPECT_GT(state.plastic_slip, 0.0);
    EXPECT_LT(state.force.norm(), f.stiffness * du);
    EXPECT_LT(relative_difference(state.force.norm(), f.yield_force(state.plastic_slip)), 1e-10);
  }
}

TEST(ContinuouslyYielding, MonotonicLoadingFollowsTheExactCurveToFullFriction) {
  const Fixture f;
  const double du = f.peak / 50.0;
  ShearState state;
  double u = 0.0, previous = 0.0;
  for (int i = 0; i < 50 * 30; ++i) {
    const ShearResult r = update_shear(f.law, state, step_along(Eigen::Vector3d(du, 0, 0)));
    u += du;
    ASSERT_TRUE(r.sliding);
    const double force = state.force.norm();
    // On the yield surface of the current step's beta (eq 16), to the root finder's tolerance.
    EXPECT_LT(relative_difference(force, f.yield_force(state.plastic_slip)), 1e-10) << i;
    // Backward Euler is exact here: u = beta + |F| / k, and |F| matches the exact solution.
    EXPECT_LT(relative_difference(state.plastic_slip + force / f.stiffness, u), 1e-12) << i;
    EXPECT_LT(relative_difference(force, exact_monotonic_force(f, u)), 1e-9) << i;
    EXPECT_GT(force, previous);
    EXPECT_EQ(state.force.y(), 0.0);
    previous = force;
  }
  // After 30 u_peak of slip, tau / sigma_n = tan 40 deg.
  EXPECT_LT(relative_difference(state.force.norm() / f.normal_force, kMu0), 1e-10);
}

/// Runs a path of increments, with normal stresses, and returns the force after every `stride`
/// steps.
std::vector<Eigen::Vector3d> run_path(const ContinuouslyYieldingShear& law,
                                      const std::vector<Eigen::Vector3d>& increments,
                                      const std::vector<double>& stresses, int stride) {
  ShearState state;
  std::vector<Eigen::Vector3d> samples;
  for (std::size_t i = 0; i < increments.size(); ++i) {
    update_shear(law, state, step_along(increments[i], stresses[i]));
    if ((i + 1) % stride == 0) samples.push_back(state.force);
  }
  return samples;
}

/// An L-shaped path (3 u_peak along x, then 3 u_peak along y, then back 2 u_peak along x) in
/// `steps_per_peak` steps per u_peak, with the normal stress rising from 0.3 to 0.6 MPa.
void l_path(const Fixture& f, int steps_per_peak, std::vector<Eigen::Vector3d>& increments,
            std::vector<double>& stresses) {
  const double du = f.peak / steps_per_peak;
  const int leg = 3 * steps_per_peak;
  for (int i = 0; i < leg; ++i) increments.emplace_back(du, 0, 0);
  for (int i = 0; i < leg; ++i) increments.emplace_back(0, du, 0);
  for (int i = 0; i < 2 * steps_per_peak; ++i) increments.emplace_back(-du, 0, 0);
  const double n = static_cast<double>(increments.size());
  for (std::size_t i = 0; i < increments.size(); ++i) {
    stresses.push_back(0.3e6 + 0.3e6 * static_cast<double>(i + 1) / n);
  }
}

TEST(ContinuouslyYielding, HalvingTheIncrementChangesTheCurveByLessThanHalfAPercent) {
  // Coarse: 40 increments per u_peak (0.8 um at 0.5 MPa), far coarser than a DEM time step. On
  // this non-radial path backward Euler is first order (on radial paths it is exact, see above);
  // the largest change is on the last leg, which runs across the force left by the second.
  const Fixture f;
  std::vector<Eigen::Vector3d> coarse_du, fine_du;
  std::vector<double> coarse_sigma, fine_sigma;
  l_path(f, 40, coarse_du, coarse_sigma);
  l_path(f, 80, fine_du, fine_sigma);
  const auto coarse = run_path(f.law, coarse_du, coarse_sigma, 1);
  const auto fine = run_path(f.law, fine_du, fine_sigma, 2);
  ASSERT_EQ(coarse.size(), fine.size());
  double largest = 0.0, worst = 0.0;
  for (const auto& force : fine) largest = std::max(largest, force.norm());
  for (std::size_t i = 0; i < coarse.size(); ++i) {
    worst = std::max(worst, (coarse[i] - fine[i]).norm() / largest);
  }
  EXPECT_LT(worst, 5e-3);
  // First-order convergence: the next halving changes the curve about half as much.
  std::vector<Eigen::Vector3d> finer_du;
  std::vector<double> finer_sigma;
  l_path(f, 160, finer_du, finer_sigma);
  const auto finer = run_path(f.law, finer_du, finer_sigma, 4);
  double next = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    next = std::max(next, (fine[i] - finer[i]).norm() / largest);
  }
  EXPECT_LT(next, 0.7 * worst);
  EXPECT_GT(next, 0.3 * worst);
}

TEST(ContinuouslyYielding, UnloadingIsElasticAndReyieldsOnTheHardenedSurface) {
  const Fixture f;
  ShearState state;
  for (int i = 0; i < 100; ++i) {
    update_shear(f.law, state, step_along(Eigen::Vector3d(f.peak / 20, 0, 0)));
  }
  const double beta = state.plastic_slip;
  const double yield = f.yield_force(beta);
  ASSERT_LT(relative_difference(-state.force.x(), yield), 1e-10);
  // Reverse: each step lowers |F| by exactly k A |du| with beta fixed, through zero and on to the
  // opposite side of the same (hardened) yield surface.
  const double du = yield / f.stiffness / 25.0;
  for (int i = 0; i < 49; ++i) {
    const double before = state.force.x();
    const ShearResult r = update_shear(f.law, state, step_along(Eigen::Vector3d(-du, 0, 0)));
    EXPECT_FALSE(r.sliding) << i;
    EXPECT_NEAR(state.force.x() - before, f.stiffness * du, 1e-12 * yield) << i;
    EXPECT_EQ(state.plastic_slip, beta);
  }
  const ShearResult r = update_shear(f.law, state, step_along(Eigen::Vector3d(-2.0 * du, 0, 0)));
  EXPECT_TRUE(r.sliding);
  EXPECT_GT(state.plastic_slip, beta);
  EXPECT_LT(relative_difference(state.force.x(), f.yield_force(state.plastic_slip)), 1e-10);
}

TEST(ContinuouslyYielding, NoDisplacementKeepsTheState) {
  const Fixture f;
  ShearState state;
  for (int i = 0; i < 30; ++i) {
    update_shear(f.law, state, step_along(Eigen::Vector3d(f.peak / 10, f.peak / 30, 0)));
  }
  const ShearState before = state;
  update_shear(f.law, state, step_along(Eigen::Vector3d::Zero()));
  EXPECT_LT((state.force - before.force).norm(), 1e-10 * before.force.norm());
  EXPECT_LT(state.plastic_slip - before.plastic_slip, 1e-10 * f.peak);
}

TEST(ContinuouslyYielding, LosingNormalForceSlidesBackToTheYieldSurface) {
  // Halving F_n at rest: the force returns to the yield surface, beta grows a little and the force
  // keeps its direction.
  const Fixture f;
  ShearState state;
  for (int i = 0; i < 40; ++i) {
    update_shear(f.law, state, step_along(Eigen::Vector3d(f.peak / 20, -f.peak / 40, 0)));
  }
  const ShearState before = state;
  const ShearResult r =
      update_shear(f.law, state, step_along(Eigen::Vector3d::Zero(), 0.5 * kStress));
  EXPECT_TRUE(r.sliding);
  EXPECT_GT(state.plastic_slip, before.plastic_slip);
  const double peak =
      f.law.power_laws.peak_displacement(0.5 * kStress);  // u_peak at the new stress
  const double mu = -kMu0 * std::expm1(-state.plastic_slip / peak);
  EXPECT_LT(relative_difference(state.force.norm(), mu * 0.5 * kStress * kArea), 1e-10);
  EXPECT_LT((state.force.normalized() - before.force.normalized()).norm(), 1e-14);
  EXPECT_GT(r.plastic_work, 0.0);
}

TEST(ContinuouslyYielding, OpenJointDropsTheForceAndKeepsTheSlip) {
  const Fixture f;
  ShearState state;
  for (int i = 0; i < 10; ++i)
    update_shear(f.law, state, step_along(Eigen::Vector3d(f.peak / 5, 0, 0)));
  const double beta = state.plastic_slip;
  const ShearResult r = update_shear(f.law, state, step_along(Eigen::Vector3d(f.peak, 0, 0), 0.0));
  EXPECT_EQ(state.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(state.plastic_slip, beta);
  EXPECT_FALSE(r.sliding);
  // Closing again, the joint keeps its hardened friction: a small step stays elastic.
  const ShearResult again =
      update_shear(f.law, state, step_along(Eigen::Vector3d(1e-3 * f.peak, 0, 0)));
  EXPECT_FALSE(again.sliding);
}

TEST(ContinuouslyYielding, PlasticMultiplierSatisfiesEq15) {
  // F = F_t / (k Lambda + 1) with F_t = F_0 - k du (eq 15 in the force-on-B convention) and
  // beta - beta_0 = Lambda |F| (eq 14).
  const Fixture f;
  ShearState state;
  for (int i = 0; i < 7; ++i)
    update_shear(f.law, state, step_along(Eigen::Vector3d(f.peak / 7, 0, 0)));
  const ShearState before = state;
  const Eigen::Vector3d du(f.peak / 9, f.peak / 13, 0);
  const ShearResult r = update_shear(f.law, state, step_along(du));
  ASSERT_TRUE(r.sliding);
  const Eigen::Vector3d trial = before.force - f.stiffness * du;
  EXPECT_LT((state.force - trial / (f.stiffness * r.plastic_multiplier + 1.0)).norm(),
            1e-12 * trial.norm());
  EXPECT_LT(relative_difference(state.plastic_slip - before.plastic_slip,
                                r.plastic_multiplier * state.force.norm()),
            1e-12);
}

}  // namespace
}  // namespace blockdem
