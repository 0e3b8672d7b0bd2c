// Joint laws given anew between stages: a block bonded by cohesion on an incline, consolidated
// elastic, then given a law that holds it or one that does not. The closed form of the limit:
// W sin ψ = c A + W cos ψ tan φ (a block on an incline with cohesion).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "blockdem/run/scene_builders.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace staged_laws_test {
namespace {

// A 4 x 2 x 3 m box cut by one joint dipping ψ = 30 degrees east through its centre; the lower
// part is fixed. The upper part (12 m³, W = 2500 x 9.81 x 12 = 294,300 N) rests on the joint,
// whose area is 2 x 4 / cos 30° = 9.2376 m². With φ = 20° it needs the cohesion
// c* = W (sin ψ - cos ψ tan φ) / A = 5,888 Pa.
constexpr double kWeight = 2500.0 * 9.81 * 12.0;
constexpr double kArea = 2.0 * 4.0 / 0.8660254037844387;

double needed_cohesion() {
  const double psi = std::numbers::pi / 6.0, phi = 20.0 * std::numbers::pi / 180.0;
  return kWeight * (std::sin(psi) - std::cos(psi) * std::tan(phi)) / kArea;
}

// Stages: gravity with J1 as `first` (a law name or "elastic"), then J1 given `second`.
std::string incline(const std::string& first, const std::string& second, double cohesion) {
  return R"(
[settings]
rounding_distance = 0.005
[[joint_laws]]
name = "rough"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 40 }
[[joint_laws]]
name = "bonded"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 20, cohesion = )" +
         std::to_string(cohesion) + R"( }
[rock_mass]
region = { min = [0, 0, 0], max = [4, 2, 3] }
density = 2500
law = "rough"
[[joint_sets]]
name = "J1"
dip_deg = 30
dip_direction_deg = 90
spacing = 100
origin = [2, 1, 1.5]
law = "bonded"
[[boundaries]]
faces = ["z_min"]
[[stages]]
name = "consolidate"
gravity = [0, 0, -9.81]
ramp_steps = 2000
damping = 0.7
max_steps = 20000
set_laws = [{ joint_set = "J1", law = ")" +
         first + R"(" }]
[[stages]]
name = "strength"
damping = 0.7
max_steps = 20000
reset_displacements = true
set_laws = [{ joint_set = "J1", law = ")" +
         second + R"(" }]
)";
}

struct Outcome {
  bool first_converged = false;
  std::int64_t broken_after_first = 0, broken_after_second = 0;
  double travel = 0.0;  // displacement of the upper block in the second stage (m)
  std::vector<std::array<std::int64_t, 2>> by_set;  // World::broken_bonds_by_set at the end
};

Outcome run(const std::string& first, const std::string& second, double cohesion) {
  const Scenario sc = parse_scenario(incline(first, second, cohesion), "incline.toml");
  World w = build_world(sc);
  const int upper = w.blocks()[0].motion == Motion::fixed ? 1 : 0;
  Outcome o;
  o.first_converged = run_stage(w, sc.stages[0]).converged;
  o.broken_after_first = w.broken_bond_count();
  run_stage(w, sc.stages[1]);
  o.broken_after_second = w.broken_bond_count();
  o.by_set = w.broken_bonds_by_set();
  const Block& b = w.blocks()[upper];
  o.travel = (b.position - b.initial_position).norm();
  return o;
}

TEST(StagedLaws, ElasticConsolidationKeepsTheBondThatTheRealLawThenJudges) {
  const double c = needed_cohesion();
  ASSERT_NEAR(c, 5888.0, 1.0);
  // The real law from the start, 10% weak: the bond breaks under the gravity ramp.
  const Outcome control = run("bonded", "bonded", 0.9 * c);
  EXPECT_GT(control.broken_after_first, 0);
  // Elastic while gravity comes on: no bond breaks, whatever the law's cohesion.
  const Outcome weak = run("elastic", "bonded", 0.9 * c);
  EXPECT_TRUE(weak.first_converged);
  EXPECT_EQ(weak.broken_after_first, 0);
  // Then the real law: 10% below the limit it breaks and the block slides (more than the
  // elastic shear displacement, W sin ψ / (k_s A) = 0.16 mm); 10% above it holds.
  EXPECT_GT(weak.broken_after_second, 0);
  EXPECT_GT(weak.travel, 1e-2);
  // The bond broke on J1's face (set 0: row 1), in shear: the joint stays in compression.
  ASSERT_EQ(weak.by_set.size(), 2u);
  EXPECT_EQ(weak.by_set[1][1], weak.broken_after_second);
  EXPECT_EQ(weak.by_set[1][0], 0);
  EXPECT_EQ(weak.by_set[0][0] + weak.by_set[0][1], 0);
  const Outcome strong = run("elastic", "bonded", 1.1 * c);
  EXPECT_EQ(strong.broken_after_second, 0);
  // Displacements count from the second stage's start: the block moved only as the shear
  // spring took the load the elastic twin carried with the same stiffness, i.e. not at all.
  EXPECT_LT(strong.travel, 1e-6);
}

// Giving J1 the law it has (set_laws that change nothing) leaves the run bit for bit as it is
// without set_laws: every block's pose and velocity, and every contact's forces, after both
// stages. Reference: the same scenario without the set_laws lines.
TEST(StagedLaws, ALawChangeThatChangesNothingLeavesTheRunBitIdentical) {
  const std::string with = incline("bonded", "bonded", 0.9 * needed_cohesion());
  std::string without = with;
  for (std::size_t at; (at = without.find("set_laws")) != std::string::npos;)
    without.erase(at, without.find('\n', at) - at + 1);
  ASSERT_EQ(without.find("set_laws"), std::string::npos);
  const auto run_both = [](const std::string& text) {
    const Scenario sc = parse_scenario(text, "incline.toml");
    World w = build_world(sc);
    for (const Stage& st : sc.stages) run_stage(w, st);
    return w;
  };
  const World a = run_both(with);
  const World b = run_both(without);
  ASSERT_EQ(a.step_count(), b.step_count());
  ASSERT_GT(a.broken_bond_count(), 0) << "the case must do something: its bond breaks";
  for (std::size_t i = 0; i < a.blocks().size(); ++i) {
    EXPECT_EQ(a.blocks()[i].position, b.blocks()[i].position);
    EXPECT_EQ(a.blocks()[i].orientation.coeffs(), b.blocks()[i].orientation.coeffs());
    EXPECT_EQ(a.blocks()[i].velocity, b.blocks()[i].velocity);
  }
  const auto ca = a.contacts(), cb = b.contacts();
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t k = 0; k < ca.size(); ++k) {
    EXPECT_EQ(ca[k]->normal_force, cb[k]->normal_force);
    EXPECT_EQ(ca[k]->shear.force, cb[k]->shear.force);
  }
}

TEST(StagedLaws, UnknownJointSetOrLawIsAnInputError) {
  try {
    parse_scenario(incline("elastic", "nonsense", 1e4), "incline.toml");
    FAIL() << "an unknown law must be refused";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.key(), "stages[2].set_laws[1].law") << e.what();
    EXPECT_NE(e.reason().find("elastic"), std::string::npos) << e.what();
  }
  std::string text = incline("elastic", "bonded", 1e4);
  text.replace(text.find("joint_set = \"J1\""), 16, "joint_set = \"J9\"");
  try {
    parse_scenario(text, "incline.toml");
    FAIL() << "an unknown joint set must be refused";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.key(), "stages[1].set_laws[1].joint_set") << e.what();
    EXPECT_NE(e.reason().find("J1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace staged_laws_test
}  // namespace blockdem
