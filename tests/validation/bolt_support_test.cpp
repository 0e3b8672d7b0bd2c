// Rock bolts against closed forms (docs/support.md):
// - a block hanging from a fixed roof by a point-anchored bolt of stiffness k: at rest the
//   tendon carries the weight W and has stretched W / k;
// - a pretensioned bolt clamping the block to the roof: the tendon starts at its pretension P
//   and ends at P - k (P - W) / (k + K_n), K_n the joint's normal stiffness times its area;
// - a tendon that yields below W is capped at its yield force, ruptures at its rupture strain,
//   and the block falls;
// - a fully grouted bolt pulled at its head (the shear-lag solution of Farmer 1975, Int. J.
//   Rock Mech. Min. Sci. 12:347; Li & Stillborg 1999, Int. J. Rock Mech. Min. Sci. 36:1013):
//   N(x) = F sinh(α(L - x)) / sinh(αL), head stiffness E A α tanh(αL), α = sqrt(k_b / (E A)),
//   and the grout yields first at the head when F = s_b tanh(αL) / α.
// Bolts and dowels holding a block on an incline: bolt_incline_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/run/scene_builders.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace bolt_support_test {
namespace {

constexpr double kDensity = 2500.0;
constexpr double kG = 9.81;

// A fixed block and a free one, of 2500 kg/m^3, boxes of the sizes given (m) centred on the
// z axis at heights z (m); the joint law linear, k_n = 1e10 Pa/m, k_s = 1e9 Pa/m, 30 degrees.
std::string two_blocks(const std::string& fixed_size, double fixed_z, const std::string& free_size,
                       double free_z) {
  std::ostringstream s;
  s.precision(17);
  s << "[settings]\ndamping = 0.7\ncontact_mode = \"face_integrated\"\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 30 }\n";
  for (int k = 0; k < 2; ++k) {
    s << "[[blocks]]\nname = \"" << (k == 0 ? "fixed" : "free")
      << "\"\ndensity = 2500\nsize = " << (k == 0 ? fixed_size : free_size)
      << "\nposition = [0, 0, " << (k == 0 ? fixed_z : free_z) << "]\n"
      << (k == 0 ? "motion = \"fixed\"\n" : "");
  }
  return s.str();
}

// A 0.5 m cube under a fixed roof (z >= 0), bolted up through its middle: collar on its bottom
// face, 1 m of bolt (0.5 m in the cube, 0.5 m in the roof). `bolt` adds keys to the bolt.
std::string hanging(const std::string& bolt, std::int64_t steps) {
  return two_blocks("[2, 2, 1]", 0.5, "[0.5, 0.5, 0.5]", -0.25) +
         "[[stages]]\nname = \"hang\"\nkind = \"steps\"\nsteps = " + std::to_string(steps) +
         "\ngravity = [0, 0, -9.81]\n"
         "[[bolts]]\nname = \"B1\"\nstart = [0, 0, -0.5]\ndirection = [0, 0, 1]\nlength = 1.0\n"
         "axial_stiffness = 1e7\ninstall_stage = \"hang\"\n" +
         bolt;
}

constexpr double kWeight = kDensity * 0.125 * kG;  // the hanging cube's (N)

// Both contact modes: the bolt's loads do not depend on how contacts are found.
class BoltContactModes : public ::testing::TestWithParam<ContactMode> {
 protected:
  World world_of(const std::string& text) {
    Scenario sc = parse_scenario(text, "hanging.toml");
    sc.settings.contact_mode = GetParam();
    stages_ = sc.stages;
    return build_world(sc);
  }
  std::vector<Stage> stages_;
};

TEST_P(BoltContactModes, PointAnchoredBoltCarriesTheWeightAndStretchesWOverK) {
  World w = world_of(hanging("", 20000));
  run_stage(w, stages_[0]);
  ASSERT_EQ(w.bolts().size(), 1u);
  const Bolt& b = w.bolts()[0];
  EXPECT_EQ(b.state, Bolt::State::intact);
  EXPECT_NEAR(b.axial_force, kWeight, 1e-6 * kWeight);
  const double drop = -(w.blocks()[1].position.z() + 0.25);
  EXPECT_NEAR(drop, kWeight / 1e7, 1e-6 * kWeight / 1e7);
  std::printf("hanging bolt (%s): N / W - 1 = %.2e, stretch k / W - 1 = %.2e\n",
              to_string(GetParam()), b.axial_force / kWeight - 1.0, drop * 1e7 / kWeight - 1.0);
  EXPECT_EQ(w.contact_count(), 0u);  // the joint has opened
}

TEST_P(BoltContactModes, PretensionStartsAtPAndClampsTheBlockToTheRoof) {
  const double p = 5000.0;  // above the weight: the joint stays closed
  World w = world_of(hanging("pretension = 5000\n", 1));
  run_stage(w, stages_[0]);
  // After the first step (forces at the installed pose): the pretension exactly.
  EXPECT_EQ(w.bolts()[0].axial_force, p);
  Stage more;
  more.name = "rest";
  more.kind = Stage::Kind::steps;
  more.steps = 20000;
  run_stage(w, more);
  // The block rises by δ = (P - W) / (k + K_n): the joint closes, the tendon shortens.
  const double k = 1e7, kn = 1e10 * 0.25;
  const double expected = p - k * (p - kWeight) / (k + kn);
  EXPECT_NEAR(w.bolts()[0].axial_force, expected, 1e-6 * expected);
  std::printf("pretensioned bolt (%s): N / expected - 1 = %.2e\n", to_string(GetParam()),
              w.bolts()[0].axial_force / expected - 1.0);
  EXPECT_EQ(w.contact_count(), 1u);
}

INSTANTIATE_TEST_SUITE_P(BoltSupport, BoltContactModes,
                         ::testing::Values(ContactMode::face_integrated, ContactMode::boon2012),
                         [](const ::testing::TestParamInfo<ContactMode>& mode) {
                           return std::string(to_string(mode.param));
                         });

TEST(BoltSupport, TendonYieldsAtItsYieldForceThenRupturesAndTheBlockFalls) {
  const double fy = 0.5 * kWeight;
  std::ostringstream keys;
  keys.precision(17);
  keys << "yield_force = " << fy << "\nrupture_strain = 0.05\n";
  const Scenario sc = parse_scenario(hanging(keys.str(), 1), "rupture.toml");
  World w = build_world(sc);
  run_stage(w, sc.stages[0]);
  double largest = 0.0, drop_at_rupture = 0.0;
  for (int k = 0; k < 200000 && w.bolts()[0].active(); ++k) {
    w.step();
    largest = std::max(largest, w.bolts()[0].axial_force);
    drop_at_rupture = -(w.blocks()[1].position.z() + 0.25);
  }
  const Bolt& b = w.bolts()[0];
  ASSERT_EQ(b.state, Bolt::State::ruptured);
  EXPECT_LE(largest, fy * (1.0 + 1e-12));
  EXPECT_NEAR(largest, fy, 1e-12 * fy);
  // Ruptured when the tendon's strain passed 5 %: the 1 m bolt had stretched 5 cm (to the
  // block's travel in the step it broke).
  EXPECT_NEAR(drop_at_rupture, 0.05, 0.001);
  EXPECT_EQ(w.bolt_count(Bolt::State::ruptured), 1);
  // Then the block falls freely.
  const double v0 = w.blocks()[1].velocity.z();
  for (int k = 0; k < 1000; ++k) w.step();
  EXPECT_LT(w.blocks()[1].velocity.z(), v0);
  EXPECT_EQ(b.axial_force, 0.0);
}

// Pull-out: rock A fixed (2 m deep along the bolt), a thin plate B above it pulled up by F; the
// bolt goes from B's top face through the joint and 2 m into A. E A = 1e8 N, k_b = 1e8 N/m/m:
// α = 1 /m, αL = 2.
struct PullOut {
  World world;
  double crossing = 0.0;  // arc length of the joint (m)
};

constexpr double kEA = 1e8, kBond = 1e8, kEmbedded = 2.0, kPlate = 0.002;

PullOut pull(double force, double bond_strength) {
  const std::string text = two_blocks("[1, 1, 2]", -1.0, "[0.2, 0.2, 0.002]", 0.001) +
                           "[[stages]]\nname = \"none\"\nkind = \"steps\"\nsteps = 1\n";
  const Scenario sc = parse_scenario(text, "pull_out.toml");
  PullOut p{build_world(sc)};
  World& w = p.world;
  BoltSpec b;
  b.name = "grouted";
  b.start = Eigen::Vector3d(0, 0, kPlate);
  b.direction = -Eigen::Vector3d::UnitZ();
  b.length = kEmbedded + kPlate;
  b.axial_stiffness = kEA / b.length;
  b.bond_stiffness = kBond;
  b.bond_strength = bond_strength;
  Stage st;
  st.name = "pull";
  st.kind = Stage::Kind::steps;
  st.steps = 1;
  st.bolts = {b};
  run_stage(w, st);
  // The pull raised over 20000 steps (quasi-static: no overshoot), then held.
  constexpr int kRamp = 20000;
  for (int k = 1; k <= 2 * kRamp; ++k) {
    w.blocks()[1].set_external_force(Eigen::Vector3d(0, 0, force * std::min(1.0, 1.0 * k / kRamp)));
    w.step();
  }
  p.crossing = w.bolts()[0].crossings.at(0).at;
  return p;
}

TEST(BoltSupport, GroutedBoltInPullOutFollowsTheShearLagSolution) {
  const double f = 1e4;
  const PullOut p = pull(f, std::numeric_limits<double>::infinity());
  const Bolt& b = p.world.bolts()[0];
  const double alpha = std::sqrt(kBond / kEA), l = kEmbedded;
  // The axial force along the embedded length, at each element's middle.
  double worst = 0.0;
  for (std::size_t e = 0; e < b.tendon.elements.size(); ++e) {
    const double mid = 0.5 * (b.node_at[e] + b.node_at[e + 1]) - p.crossing;
    if (mid < 0.0) continue;  // in the plate
    const double expected = f * std::sinh(alpha * (l - mid)) / std::sinh(alpha * l);
    worst = std::max(worst, std::abs(b.tendon.elements[e].force - expected) / f);
  }
  EXPECT_LT(worst, 0.02) << "largest error of N(x) over F";
  // The head stiffness of the embedded length: the force entering the rock over the tendon's
  // displacement at the joint.
  std::size_t node = 0;
  while (b.node_at[node] < p.crossing - 1e-12) ++node;
  double into_rock = 0.0;
  for (std::size_t k = 0; k < b.tendon.springs.size(); ++k) {
    if (b.ties[k].block == 0) into_rock -= b.tendon.springs[k].force;  // along -d: out
  }
  EXPECT_NEAR(into_rock, f, 1e-6 * f);
  const double stiffness = into_rock / -b.tendon.u[node];
  const double expected = kEA * alpha * std::tanh(alpha * l);
  EXPECT_NEAR(stiffness, expected, 0.02 * expected);
  std::printf(
      "grouted pull-out: largest |N(x) - closed form| / F = %.2e, head stiffness %.6g "
      "N/m against %.6g (%.2e)\n",
      worst, stiffness, expected, stiffness / expected - 1.0);
  EXPECT_EQ(b.state, Bolt::State::intact);
}

TEST(BoltSupport, GroutYieldsFirstAtTheHeadAtTheShearLagLoad) {
  const double strength = 1e4;  // s_b (N/m)
  const double alpha = std::sqrt(kBond / kEA);
  const double first_yield = strength * std::tanh(alpha * kEmbedded) / alpha;
  EXPECT_EQ(pull(0.98 * first_yield, strength).world.bolts()[0].state, Bolt::State::intact);
  const PullOut above = pull(1.02 * first_yield, strength);
  const Bolt& b = above.world.bolts()[0];
  EXPECT_EQ(b.state, Bolt::State::yielded);
  // The grout slipped at the joint, not at the far end.
  double slip_near = 0.0, slip_far = 0.0;
  for (std::size_t k = 0; k < b.tendon.springs.size(); ++k) {
    if (b.ties[k].block != 0) continue;
    const double s = b.node_at[static_cast<std::size_t>(b.tendon.springs[k].node)];
    if (s < above.crossing + 0.1)
      slip_near = std::max(slip_near, std::abs(b.tendon.springs[k].slip));
    if (s > above.crossing + 1.0) slip_far = std::max(slip_far, std::abs(b.tendon.springs[k].slip));
  }
  EXPECT_GT(slip_near, 0.0);
  EXPECT_EQ(slip_far, 0.0);
}

}  // namespace
}  // namespace bolt_support_test
}  // namespace blockdem
