// Viscous contact damping (response/contact_damping.hpp) against closed forms: the restitution of
// a block bouncing off a fixed base on a linear joint, the energy its dashpot dissipates, the
// energy budget with the dashpot on, bit-identical results for 1 and 2 threads, and the base's
// work of a dynamic stage in the budget. Each test states its reference and tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "blockdem/run/scene_builders.hpp"
#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stage.hpp"
#include "brick_pile.hpp"
#include "scenes.hpp"
#include "shaken_block.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::test::contact_damping_test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRho = 2500.0;  // (kg/m^3)
constexpr double kKn = 1e10;     // (Pa/m)
constexpr double kKs = 1e9;      // (Pa/m)

// Restitution of a linear spring-dashpot whose dashpot may pull: the overlap returns to zero
// after π / ω, ω = ω0 sqrt(1 - ζ²).
double restitution_with_pull(double zeta) {
  return std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta));
}

// Without the pull (this model): the block leaves when the total force is zero, at
// ω t = π - 2 arctan(β / ω), β = ζ ω0 (Schwager & Pöschel 2007, Granular Matter 9, 465-469).
double restitution_without_pull(double zeta) {
  const double beta_over_omega = zeta / std::sqrt(1.0 - zeta * zeta);
  return std::exp(-beta_over_omega * (kPi - 2.0 * std::atan(beta_over_omega)));
}

struct Bounce {
  double restitution = 0.0;        ///< rebound speed over impact speed (-)
  double dissipated = 0.0;         ///< the budget's contact_damping at the end (J)
  double kinetic_lost = 0.0;       ///< ½ m (v0² - v1²) (J)
  double worst_residual = 0.0;     ///< max |residual| / scale over the steps (-)
  double least_total_force = 0.0;  ///< min over steps of (F_n + F_d) / F_n peak (-)
  bool cut = false;                ///< the dashpot was cut at some step (no pull)
};

// A 0.1 m cube moving at v0 = 0.1 m/s onto a fixed base, no gravity, a linear normal law; the
// time step τ/400, τ = sqrt(m / (k_n A)): the leapfrog's phase error is (Δt/τ)²/24, and the
// dashpot's use of the velocity half a step before the spring's position changes the damping
// by O(Δt/τ), both well below 1e-3.
Bounce bounce(ContactMode mode, double zeta) {
  WorldSettings s;
  s.contact_mode = mode;
  s.contact_damping = zeta;
  const double a = 0.1, gap = 1e-4, v0 = 0.1;
  const double m = kRho * a * a * a;
  const double tau = std::sqrt(m / (kKn * a * a));
  s.time_step = tau / 400.0;
  World w = linear_world(kKn, kKs, 30, s);
  w.add_block(box_block({0.5, 0.5, 0.1}, {0, 0, -0.05}, kRho, Motion::fixed, "base"));
  Block cube = box_block({a, a, a}, {0, 0, a / 2 + gap}, kRho);
  cube.velocity = {0, 0, -v0};
  w.add_block(cube);
  Bounce out;
  double peak = 0.0, least = 0.0;
  bool touched = false;
  while (w.time() < gap / v0 + 20.0 * tau) {
    w.step();
    const EnergyBudget& e = w.energy_budget();
    out.worst_residual = std::max(out.worst_residual, std::abs(e.residual()) / e.scale());
    for (const Contact* c : w.contacts()) {
      touched = true;
      peak = std::max(peak, c->normal_force);
      least = std::min(least, c->normal_force + c->damping_force());
      if (c->damping_force() < 0.0 && c->damping_force() == -c->normal_force) out.cut = true;
    }
    if (touched && w.contact_count() == 0) break;
  }
  EXPECT_TRUE(touched);
  EXPECT_EQ(w.contact_count(), 0u) << "the cube must have left the base";
  // A few steps of free flight: the budget's kinetic energy is then ½ m v1².
  for (int k = 0; k < 5; ++k) w.step();
  const double v1 = w.blocks()[1].velocity.z();
  out.restitution = v1 / v0;
  out.dissipated = w.energy_budget().contact_damping;
  out.kinetic_lost = 0.5 * m * (v0 * v0 - v1 * v1);
  out.least_total_force = least / peak;
  return out;
}

class Restitution : public ::testing::TestWithParam<std::tuple<ContactMode, double>> {};

// Reference: Schwager & Pöschel's restitution of the dashpot without pull, tolerance 1%; at
// ζ = 0.05 also the classic exp(-ζ π / sqrt(1 - ζ²)) (0.5% apart), 1%. The dashpot's energy is
// the kinetic energy lost, ½ m (v0² - v1²), to 1e-3 (the budget's residual over the bounce is
// the step in which the contact forms, (Δt/τ)²/4 of the impact energy); the budget closes to 1%
// of its largest term at every step. The total normal force never pulls (>= -1e-12 of the peak).
TEST_P(Restitution, MatchesTheSpringDashpotClosedForm) {
  const auto [mode, zeta] = GetParam();
  const Bounce b = bounce(mode, zeta);
  const double expected = restitution_without_pull(zeta);
  std::printf(
      "[restitution %s zeta %.2f] e = %.5f, closed form without pull %.5f (%+.3f%%), with pull "
      "%.5f; dissipated %.6e J, kinetic lost %.6e J; worst residual ratio %.2e\n",
      to_string(mode), zeta, b.restitution, expected, 100.0 * (b.restitution / expected - 1.0),
      restitution_with_pull(zeta), b.dissipated, b.kinetic_lost, b.worst_residual);
  EXPECT_NEAR(b.restitution, expected, 0.01 * expected);
  if (zeta <= 0.05) {
    EXPECT_NEAR(b.restitution, restitution_with_pull(zeta), 0.01 * restitution_with_pull(zeta));
  }
  EXPECT_NEAR(b.dissipated, b.kinetic_lost, 1e-3 * b.kinetic_lost);
  EXPECT_LT(b.worst_residual, 0.01);
  EXPECT_GE(b.least_total_force, -1e-12);
  EXPECT_TRUE(b.cut) << "the dashpot must have been cut as the cube left";
}

INSTANTIATE_TEST_SUITE_P(
    ModesAndRatios, Restitution,
    ::testing::Combine(::testing::Values(ContactMode::boon2012, ContactMode::face_integrated),
                       ::testing::Values(0.05, 0.2)),
    [](const auto& p) {
      return std::string(to_string(std::get<0>(p.param))) + "_zeta_" +
             std::to_string(static_cast<int>(std::lround(100.0 * std::get<1>(p.param))));
    });

// Without the key (ζ = 0) the bounce is elastic: e = 1 to 1e-3 (the leapfrog conserves the
// budget's energy to the contact-forming step) and no energy goes to a dashpot (exactly 0).
TEST(ContactDamping, OffByDefault) {
  const Bounce b = bounce(ContactMode::face_integrated, 0.0);
  EXPECT_NEAR(b.restitution, 1.0, 1e-3);
  EXPECT_EQ(b.dissipated, 0.0);
  EXPECT_FALSE(b.cut);
}

// Bits of every block and contact and of the energy budget, per step.
std::vector<std::vector<double>> pile_run(int threads, ContactMode mode, int steps) {
  WorldSettings s;
  s.gravity = Eigen::Vector3d(60.0, 25.0, -98.1);
  s.contact_mode = mode;
  s.threads = threads;
  s.contact_damping = 0.1;
  World w = BrickPile{}.world(s, 20.0);
  std::vector<std::vector<double>> out;
  for (int k = 0; k < steps; ++k) {
    w.step();
    std::vector<double> rec;
    for (const Block& b : w.blocks()) {
      for (const Eigen::Vector3d* v : {&b.position, &b.velocity, &b.angular_velocity, &b.force})
        rec.insert(rec.end(), v->data(), v->data() + 3);
    }
    for (const Contact* c : w.contacts()) {
      rec.push_back(c->normal_force);
      rec.push_back(c->damping_force());
      rec.push_back(c->damping_work());
    }
    const EnergyBudget& e = w.energy_budget();
    rec.push_back(e.contact_damping);
    rec.push_back(e.residual());
    out.push_back(std::move(rec));
  }
  EXPECT_GT(w.energy_budget().contact_damping, 0.0);
  return out;
}

// Oracle: the serial run; tolerance none (every bit, compared as doubles with ==, which here
// holds no NaN). A brick pile sliding under a tilted 10 g with ζ = 0.1.
TEST(ContactDamping, BitIdenticalForOneAndTwoThreads) {
  for (const ContactMode mode : {ContactMode::boon2012, ContactMode::face_integrated}) {
    const int steps = 60;
    const auto one = pile_run(1, mode, steps), two = pile_run(2, mode, steps);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t k = 0; k < one.size(); ++k)
      ASSERT_TRUE(one[k] == two[k]) << to_string(mode) << ": first difference at step " << k + 1;
  }
}

// A 0.4 x 0.4 x 0.2 m block on a fixed plate (group "base", friction 30°) that a dynamic stage
// shakes with a sine pulse, 6 m/s² peak (above the yield acceleration g tan 30° = 5.66 m/s²:
// the block slips). Its energy budget's residual over the shaking, relative to the base's work.
// `zeta`: contact damping.
double shaken_residual_ratio(const std::string& mode, double zeta) {
  std::ostringstream settings;
  settings << "contact_damping = " << zeta << "\ncontact_mode = \"" << mode << "\"\n";
  const std::string text = shaken_block_scenario(
      settings.str(), "",
      "[[stages]]\nname = \"shake\"\nkind = \"dynamic\"\nduration = 0.4\n"
      "base_motion = { group = \"base\", pulse = \"sine\", amplitude_m_s2 = 6.0, period = 0.2, "
      "cycles = 2, direction = [1, 0, 0] }\n");
  const Scenario sc = parse_scenario(text, "shaken.toml");
  World world = build_world(sc);
  double before = 0.0, boundary_before = 0.0, worst = 0.0;
  for (const Stage& st : sc.stages) {
    const bool dynamic = st.kind == Stage::Kind::dynamic;
    if (dynamic) {
      before = world.energy_budget().residual();
      boundary_before = world.energy_budget().boundary_work;
    }
    const StepFn on_step = [&](const World& w, const Stage&, std::int64_t) {
      if (dynamic) worst = std::max(worst, std::abs(w.energy_budget().residual() - before));
    };
    const StageResult r = run_stage(world, st, {}, nullptr, {}, nullptr, on_step);
    EXPECT_TRUE(r.converged) << st.name << ": " << r.message;
  }
  const EnergyBudget& e = world.energy_budget();
  const double work = std::abs(e.boundary_work - boundary_before);
  std::printf(
      "[shaken %s zeta %.2f] base work %.6e J, friction %.6e J, contact damping %.6e J, worst "
      "residual change %.3e J (%.2e of the base work)\n",
      mode.c_str(), zeta, work, e.friction_dissipation, e.contact_damping, worst, worst / work);
  EXPECT_GT(work, 0.1);
  return worst / work;
}

// The base's work is paired with the velocity that moved it over each step (set after the
// step): the budget of the shaken block (face_integrated) closes to the slip terms' own error.
// Before, the base's velocity of the step before was used: the residual grew to 0.107 of the
// base's work over this stage (1.5e-2 J of 0.145 J). Measured now 1.9e-6 (ζ = 0) and 4.6e-6
// (ζ = 0.1); tolerance 1e-4 of the base's work. (In mode boon2012 the point contact's elastic
// estimate of a rocking block, not the base, dominates the residual: docs/outputs.md.)
TEST(ShakenLedger, ClosesOverTheShaking) {
  EXPECT_LT(shaken_residual_ratio("face_integrated", 0.0), 1e-4);
  EXPECT_LT(shaken_residual_ratio("face_integrated", 0.1), 1e-4);
}

}  // namespace
}  // namespace blockdem::test::contact_damping_test
