// A rock bridge in a cut rock mass: a 1 x 1 x 2 m column cut at mid-height by one disc joint far
// smaller than the column, so that the whole cut face is bonded (intact rock). The top face is
// fixed; the lower block hangs from the bridge under gravity. Limit: it holds while its weight
// W = rho g V is below sigma_t A (A = 1 m^2), stretching the bridge by W / (k_n A); with
// sigma_t A < W the bridge breaks in tension and the block falls.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem {
namespace {

std::string column(double tensile_strength) {
  return R"(
[settings]
damping = 0.7
contact_mode = "boon2012"
rounding_distance = 0.01
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 30 }
[[joint_laws]]
name = "bridge"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 45, cohesion = 1e6, tensile_strength = )" +
         std::to_string(tensile_strength) + R"( }
[rock_mass]
region = { min = [0, 0, 0], max = [1, 1, 2] }
density = 2700
law = "joint"
bonded_law = "bridge"
[[joint_sets]]
dip_deg = 0
dip_direction_deg = 0
origin = [0.5, 0.5, 1]
extent = { radius = 0.05, centres = [[0.5, 0.5, 1]] }
[[boundaries]]
faces = ["z_max"]
[[stages]]
name = "hang"
kind = "duration"
gravity = [0, 0, -9.81]
duration = 0.05
)";
}

constexpr double kWeight = 2700.0 * 9.81 * 1.0;  // the lower block, 1 m^3 (N)

TEST(RockBridge, HoldsTheHangingBlockBelowItsTensileStrength) {
  const Scenario sc = parse_scenario(column(4.0 * kWeight), "bridge.toml");
  World w = build_world(sc);
  ASSERT_EQ(w.blocks().size(), 2u);
  const int lower = w.blocks()[0].position.z() < 1.0 ? 0 : 1;
  const double z0 = w.blocks()[static_cast<std::size_t>(lower)].position.z();
  run_stage(w, sc.stages[0]);
  const double stretch = kWeight / 1e9;  // W / (k_n A) (m)
  const Block& b = w.blocks()[static_cast<std::size_t>(lower)];
  EXPECT_EQ(w.broken_bond_count(), 0);
  ASSERT_EQ(w.contact_count(), 1u);
  EXPECT_NEAR(w.contacts().front()->normal_force, -kWeight, 0.02 * kWeight);
  EXPECT_NEAR(b.position.z(), z0 - stretch, 0.05 * stretch);
}

TEST(RockBridge, BreaksAndTheBlockFallsAboveItsTensileStrength) {
  const Scenario sc = parse_scenario(column(0.5 * kWeight), "bridge.toml");
  World w = build_world(sc);
  ASSERT_EQ(w.blocks().size(), 2u);
  const int lower = w.blocks()[0].position.z() < 1.0 ? 0 : 1;
  const double z0 = w.blocks()[static_cast<std::size_t>(lower)].position.z();
  run_stage(w, sc.stages[0]);
  EXPECT_EQ(w.broken_bond_count(), 1);
  EXPECT_EQ(w.contact_count(), 0u);
  // Falling freely (damping only slows it): it has dropped by far more than any elastic stretch.
  EXPECT_LT(w.blocks()[static_cast<std::size_t>(lower)].position.z(), z0 - 1e-3);
}

}  // namespace
}  // namespace blockdem
