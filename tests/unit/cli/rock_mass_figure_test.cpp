// `blockdem run` of a rock mass draws blocks_final.png (tools/plot_rock_mass.py --run-vtk) from
// the last VTK frame, a .vtu file (docs/rock-mass.md): the figure exists and no "no figures"
// warning is printed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_runner.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

TEST(RockMassFigure, RunDrawsTheBlocksAtTheEnd) {
  const auto dir = test::temp_path("rock_mass_figure");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // A 4 m cube cut by one joint set into prisms; 20 steps of settling are enough for a frame.
  const auto file = dir / "rock.toml";
  std::ofstream(file) << "title = \"rock mass\"\n[settings]\ndamping = 0.7\n"
                         "[[joint_laws]]\nname = \"joint\"\n"
                         "normal = { law = \"linear\", stiffness = 1e9 }\n"
                         "shear = { law = \"linear\", stiffness = 1e8, friction_deg = 40 }\n"
                         "[rock_mass]\nregion = { min = [0, 0, 0], max = [4, 4, 4] }\n"
                         "density = 2500.0\nlaw = \"joint\"\n"
                         "[[joint_sets]]\ndip_deg = 40\ndip_direction_deg = 90\nspacing = 2.0\n"
                         "[[boundaries]]\nfaces = [\"z_min\"]\ncondition = \"fixed\"\n"
                         "[[stages]]\nname = \"settle\"\ngravity = [0, 0, -9.81]\nmax_steps = 20\n";
  const auto out = dir / "out";
  const test::CommandOutput r =
      test::run_cli("run " + file.string() + " --out " + out.string() + " --quiet");
  EXPECT_EQ(r.exit_code, 3) << "20 steps do not settle it";
  const std::string& text = r.err;
  EXPECT_EQ(text.find("no figures"), std::string::npos) << text;
  ASSERT_TRUE(std::filesystem::exists(out / "blocks_final.png")) << text;
  EXPECT_GT(std::filesystem::file_size(out / "blocks_final.png"), 1000u);
}

}  // namespace
}  // namespace blockdem
