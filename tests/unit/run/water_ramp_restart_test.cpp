// A run stopped inside a stage whose ramp brings a water table in, and resumed, writes the same
// outputs (bytes) as the run never stopped: the restart gives the stage the water of the stages
// before it and the stage's own, and the ramp's fraction follows from the steps done.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "restart_support.hpp"
#include "support/cli_runner.hpp"

namespace blockdem::test::water_ramp_restart {
namespace {

namespace fs = std::filesystem;

TEST(WaterRampRestart, ResumingInsideTheRampIsBitIdentical) {
  const fs::path file = fresh_dir("water_ramp_restart.toml");
  {
    std::ofstream f(file);
    // Two blocks on a fixed base, half submerged; the table rises over their tops in 400 steps.
    f << R"(title = "a rising water table"
[settings]
damping = 0.3
water_table = { point = [0, 0, 0.05], normal = [0, 0, 1] }
[output]
history_interval = 7
[[materials]]
name = "rock"
density = 2600.0
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 30 }
[[blocks]]
name = "base"
material = "rock"
size = [1.0, 0.4, 0.05]
position = [0.0, 0.0, -0.025]
motion = "fixed"
[[blocks]]
name = "b1"
material = "rock"
size = [0.1, 0.1, 0.1]
position = [0.0, 0.0, 0.05]
[[blocks]]
name = "b2"
material = "rock"
size = [0.1, 0.1, 0.1]
position = [0.0, 0.0, 0.15]
[[stages]]
name = "settle"
kind = "steps"
steps = 300
gravity = [0, 0, -9.81]
[[stages]]
name = "rise"
kind = "steps"
steps = 600
ramp_steps = 400
water_table = { point = [0, 0, 0.3], normal = [0.1, 0, 1] }
)";
  }
  const auto run = [&file](const fs::path& out, const std::string& extra) {
    return run_cli("run '" + file.string() + "' --out '" + out.string() +
                   "' --quiet --no-figures --threads 1" + extra);
  };
  const fs::path reference = fresh_dir("water_ramp_restart_reference");
  const CommandOutput full = run(reference, "");
  ASSERT_EQ(full.exit_code, 0) << full.err;
  // Stopped (SIGTERM: a checkpoint, exit 143) half way through the ramp, then resumed.
  const fs::path out = fresh_dir("water_ramp_restart_resumed");
  ::setenv("BLOCKDEM_TEST_KILL_RANK", "0:500:TERM", 1);
  const CommandOutput stopped = run(out, "");
  ::unsetenv("BLOCKDEM_TEST_KILL_RANK");
  ASSERT_EQ(stopped.exit_code, 143) << stopped.err;
  const CommandOutput resumed = run(out, " --resume");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(reference, out);
  // The water acted: its force is in the summary.
  const auto summary = nlohmann::json::parse(read_file_bytes(reference / "summary.json"));
  EXPECT_GT(summary["water_force_N"].get<double>(), 0.0);
}

}  // namespace
}  // namespace blockdem::test::water_ramp_restart
