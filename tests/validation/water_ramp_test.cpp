// A water table that changes over a stage's ramp_steps: the pressure moves linearly from the one
// before the stage to the stage's, p = (1 - f) p_before + f p_stage at step k, f = k / ramp_steps.
// A block of rock 1 × 1 × 0.5 m (2600 kg/m³) rests on a fixed base; the water's force on it is
// Archimedes' rho_w g V_sub under a level table (V_sub the volume below the table at the block's
// pose), so at step k of a ramp it is (1 - f) rho_w g V_sub,before + f rho_w g V_sub,stage:
// half submerged (table 0.25 m above its base) to wholly submerged (table at 2 m), then to dry
// ("none"). Tolerance 1e-9 relative (the integration is exact; round-off).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "blockdem/scenario/scenario.hpp"
#include "blockdem/world/stage.hpp"

namespace blockdem::test::water_ramp {
namespace {

constexpr double kG = 9.81, kWater = 1000.0;

std::string block_in_water(const std::string& mode) {
  std::ostringstream t;
  t << "[settings]\ndamping = 0.7\ncontact_mode = \"" << mode << "\"\n"
    << "water_table = { point = [0.0, 0.0, 0.25], normal = [0.0, 0.0, 1.0] }\n"
    << "[[materials]]\nname = \"rock\"\ndensity = 2600.0\n"
    << "[[joint_laws]]\nname = \"joint\"\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
    << "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 30 }\n"
    << "[[blocks]]\nname = \"base\"\nmaterial = \"rock\"\nsize = [3.0, 3.0, 1.0]\n"
    << "position = [0.0, 0.0, -0.5]\nmotion = \"fixed\"\n"
    << "[[blocks]]\nname = \"block\"\nmaterial = \"rock\"\nsize = [1.0, 1.0, 0.5]\n"
    << "position = [0.0, 0.0, 0.25]\n"
    << "[[stages]]\nname = \"settle\"\ngravity = [0.0, 0.0, -9.81]\n"
    << "[[stages]]\nname = \"rise\"\nkind = \"steps\"\nsteps = 300\nramp_steps = 200\n"
    << "water_table = { point = [0.0, 0.0, 2.0], normal = [0.0, 0.0, 1.0] }\n"
    << "[[stages]]\nname = \"drain\"\nkind = \"steps\"\nsteps = 150\nramp_steps = 100\n"
    << "water_table = \"none\"\n";
  return t.str();
}

class WaterRamp : public ::testing::TestWithParam<const char*> {};

TEST_P(WaterRamp, ArchimedesForceFollowsThePressureRampedBetweenTwoTables) {
  const Scenario sc = parse_scenario(block_in_water(GetParam()), "ramp.toml");
  World w = build_world(sc);
  ASSERT_TRUE(run_stage(w, sc.stages[0]).converged);
  const int i = w.find_block("block");
  // rho_w g V_sub for a level table at z_w, the block's base at the level of the forces.
  const auto buoyancy = [&w, i](double table_z) {
    const double bottom = w.level_state(i).position.z() - 0.25;
    return kWater * kG * std::clamp(table_z - bottom, 0.0, 0.5);
  };
  // Rise (0.25 m to 2 m), then drain (2 m to none).
  struct Ramp {
    double before_z, stage_z;  // none: -inf
  };
  const Ramp ramps[] = {{0.25, 2.0}, {2.0, -INFINITY}};
  double worst = 0.0;
  int checked = 0;
  for (int s = 1; s <= 2; ++s) {
    const Stage& stage = sc.stages[static_cast<std::size_t>(s)];
    const Ramp ramp = ramps[s - 1];
    const StepFn on_step = [&](const World&, const Stage&, std::int64_t k) {
      const double f =
          std::min(1.0, static_cast<double>(k) / static_cast<double>(stage.ramp_steps));
      const double expected = (1.0 - f) * buoyancy(ramp.before_z) + f * buoyancy(ramp.stage_z);
      const Eigen::Vector3d force = w.blocks()[static_cast<std::size_t>(i)].water_force();
      const double error = (force - Eigen::Vector3d(0.0, 0.0, expected)).norm();
      worst = std::max(worst, error / (kWater * kG * 0.5));
      ++checked;
      EXPECT_LE(error, 1e-9 * kWater * kG * 0.5) << stage.name << " step " << k;
    };
    const StageResult r = run_stage(w, stage, {}, nullptr, {}, nullptr, on_step);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_FALSE(w.settings().water_ramp.has_value());
  }
  EXPECT_EQ(checked, 450);
  // Dry at the end: no water force at all.
  EXPECT_EQ(w.blocks()[static_cast<std::size_t>(i)].water_force(), Eigen::Vector3d::Zero());
  std::printf("%s: %d steps, largest error %.2e of rho_w g V\n", GetParam(), checked, worst);
}

INSTANTIATE_TEST_SUITE_P(BothModes, WaterRamp, ::testing::Values("face_integrated", "boon2012"));

}  // namespace
}  // namespace blockdem::test::water_ramp
