// A small version of scenarios/examples/tunnel.toml (a 3 m slice, 1.5 m horseshoe tunnel, three
// joint sets): the run reaches equilibrium under gravity, the excavation stage runs to its end,
// and blocks far from the tunnel barely move while it is excavated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "blockdem/run/scene_builders.hpp"

namespace blockdem {
namespace {

const char* kTunnel = R"(
[settings]
damping = 0.7
contact_mode = "boon2012"
rounding_distance = 0.01
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 30 }
[[joint_laws]]
name = "intact"
normal = { law = "linear", stiffness = 1e9 }
shear = { law = "linear", stiffness = 1e8, friction_deg = 60 }
[rock_mass]
region = { min = [0, 0, 0], max = [14, 3, 12] }
density = 2700
min_block_volume = 0.3
max_aspect_ratio = 5
law = "joint"
bonded_law = "intact"
[[joint_sets]]
dip_deg = 15
dip_direction_deg = 100
spacing = 2.6
origin = [7, 1.5, 8.3]
[[joint_sets]]
dip_deg = 70
dip_direction_deg = 230
spacing = 3.1
origin = [6.1, 1.5, 6]
[[joint_sets]]
dip_deg = 65
dip_direction_deg = 30
spacing = 3.4
origin = [8.2, 1.5, 6]
[[excavations]]
name = "tunnel"
centre = [7, 1.5, 6]
radius = 1.5
wall_height = 1.5
[[boundaries]]
faces = ["z_min"]
[[boundaries]]
faces = ["x_min", "x_max", "y_min", "y_max"]
condition = "roller"
[[stages]]
name = "gravity"
gravity = [0, 0, -9.81]
ramp_steps = 500
unbalanced_tolerance = 1e-3
kinetic_tolerance = 1e-6
max_steps = 40000
[[stages]]
name = "excavate"
kind = "duration"
excavation = "tunnel"
duration = 0.1
damping = 0.2
)";

TEST(TunnelExcavation, RunsToTheEndAndFarBlocksStayPut) {
  // Far field: blocks whose centroid lies more than two tunnel diameters (6 m) from the axis
  // (x = 7, z = 6) move less than 1 mm during excavation. Reference: the elastic unloading of
  // 1e9 Pa/m joints under at most 12 m of rock is σ/k = 2700·9.81·12/1e9 = 0.3 mm per joint.
  const Scenario sc = parse_scenario(kTunnel, "tunnel-small.toml");
  ASSERT_FALSE(sc.excavations.at("tunnel").empty());
  World w = build_world(sc);
  const StageResult settle = run_stage(w, sc.stages[0]);
  ASSERT_TRUE(settle.converged) << settle.message;
  std::vector<Eigen::Vector3d> before;
  for (const auto& b : w.blocks()) before.push_back(b.position);
  std::vector<std::string> names;
  for (const auto& b : w.blocks()) names.push_back(b.name);
  const std::size_t n = w.blocks().size();
  const StageResult dig = run_stage(w, sc.stages[1]);
  EXPECT_TRUE(dig.converged);
  ASSERT_EQ(w.blocks().size(), n - sc.excavations.at("tunnel").size());
  int far = 0;
  for (const auto& b : w.blocks()) {
    const auto it = std::find(names.begin(), names.end(), b.name);
    const Eigen::Vector3d& x0 = before[static_cast<std::size_t>(it - names.begin())];
    const double r = std::hypot(x0.x() - 7.0, x0.z() - 6.0);
    if (r <= 6.0) continue;
    ++far;
    EXPECT_LT((b.position - x0).norm(), 1e-3) << b.name;
  }
  EXPECT_GT(far, 3);
}

}  // namespace
}  // namespace blockdem
