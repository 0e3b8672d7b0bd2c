// Gradual excavation: a block bonded in tension to a fixed base carries a block three times its
// weight; removing that block at once, undamped, swings the joint from compression (W_m + W_t)
// to tension W_t - W_m = 2 W_m (a mass on a spring released from its loaded position overshoots
// its new rest by as much), which breaks a bond of tensile strength W_m / A. Taking the removed
// block's load down over many natural periods unloads the joint quasi-statically: it ends at W_m
// in compression and the bond holds.
#include <gtest/gtest.h>

#include <string>

#include "blockdem/run/scene_builders.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem {
namespace gradual_excavation_test {
namespace {

// Cubes of 0.2 m: the middle one of 2600 kg/m³ (W_m = 204 N, W_m / A = 5,101 Pa), the top one
// of 7800 kg/m³; the joint law bonds with σ_t = 5,101 Pa.
constexpr double kMiddleWeight = 2600.0 * 9.81 * 0.008;
constexpr double kArea = 0.04;

const char* kColumn = R"(
[settings]
twist = false
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 35, cohesion = 2e4, tensile_strength = 5101 }
[[blocks]]
name = "base"
density = 2600
size = [1, 1, 0.2]
position = [0, 0, -0.1]
motion = "fixed"
[[blocks]]
name = "middle"
density = 2600
size = [0.2, 0.2, 0.2]
position = [0, 0, 0.1]
[[blocks]]
name = "top"
density = 7800
size = [0.2, 0.2, 0.2]
position = [0, 0, 0.3]
[[stages]]
name = "gravity"
gravity = [0, 0, -9.81]
ramp_steps = 2000
damping = 0.7
)";

struct Outcome {
  std::int64_t broken = 0;
  double normal_force = 0.0;  // the base joint's at the end (N)
};

Outcome excavate(std::int64_t relax_steps) {
  const Scenario sc = parse_scenario(kColumn, "column.toml");
  World w = build_world(sc);
  EXPECT_TRUE(run_stage(w, sc.stages[0]).converged);
  EXPECT_EQ(w.broken_bond_count(), 0);
  Stage cut;
  cut.name = "remove the top block, undamped";
  cut.kind = Stage::Kind::steps;
  cut.remove = {"top"};
  cut.relax_steps = relax_steps;
  cut.damping = 0.0;
  cut.steps = relax_steps + 2000;
  run_stage(w, cut);
  Outcome o;
  o.broken = w.broken_bond_count();
  for (const Contact* c : w.contacts()) o.normal_force = c->normal_force;
  return o;
}

TEST(GradualExcavation, AtOnceTheReboundBreaksTheBondGraduallyItHolds) {
  EXPECT_GT(excavate(0).broken, 0);
  const Outcome gradual = excavate(4000);
  EXPECT_EQ(gradual.broken, 0);
  // At rest under its own weight, within the undamped ring-down left by the ramp's end.
  EXPECT_NEAR(gradual.normal_force, kMiddleWeight, 0.05 * kMiddleWeight);
  EXPECT_GT(gradual.normal_force / kArea, 0.0);
}

TEST(GradualExcavation, RelaxStepsWithoutAnExcavationIsAnInputError) {
  const std::string text = std::string(kColumn) + "relax_steps = 100\n";
  try {
    parse_scenario(text, "column.toml");
    FAIL() << "relax_steps without an excavation must be refused";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.key(), "stages[1].relax_steps") << e.what();
  }
}

}  // namespace
}  // namespace gradual_excavation_test
}  // namespace blockdem
