// A run's VTK output read back by VTK itself (Debian's python3-vtk9): read_vtk_output.py checks
// every frame of vtk/blocks.pvd and vtk/contacts.pvd against independent facts (box volumes,
// statics, the model times of time_history.csv); and the energy budget of time_history.csv at rest
// (Clapeyron's theorem).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../../support/cli_runner.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

// Two stacked boxes on a fixed base settle under gravity; frames every 200 steps and at the stage
// end. The base must carry the weight of both (statics; tolerance 1e-4 from the stage's
// unbalanced-force tolerance), and each polyhedron's volume, computed by VTK, is the box's
// (1e-9: round-off of the vertices).
TEST(VtuOutput, VtkReadsEveryFrameWithFields) {
  const auto dir = test::temp_path("vtu_test");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "stack.toml") << R"(title = "two stacked boxes"
[settings]
damping = 0.7
[[materials]]
name = "rock"
density = 2500.0
[[joint_laws]]
name = "joint"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 40 }
[[blocks]]
name = "base"
material = "rock"
size = [1.0, 1.0, 0.1]
position = [0.0, 0.0, -0.05]
motion = "fixed"
[[blocks]]
name = "lower"
group = "stack"
material = "rock"
size = [0.2, 0.3, 0.1]
position = [0.0, 0.0, 0.05]
[[blocks]]
name = "upper"
group = "stack"
material = "rock"
size = [0.1, 0.1, 0.05]
position = [0.02, 0.01, 0.125]
[[stages]]
name = "settle"
gravity = [0.0, 0.0, -9.81]
[output]
vtk_interval = 200
)";
  const auto run = test::run_cli("run '" + (dir / "stack.toml").string() + "' --out '" +
                                 (dir / "out").string() + "' --quiet --no-figures");
  ASSERT_EQ(run.exit_code, 0) << run.err;

  // time_history.csv's last row is the stage end at rest. The joints are linear and start
  // closed at zero closure, so by Clapeyron's theorem the stored energy is half the work of
  // gravity; tolerance 1e-2 (the elastic term is exact only at uniform closure, and the budget's
  // residual is bounded by the contact-onset error, docs/outputs.md).
  std::ifstream history(dir / "out" / "time_history.csv");
  std::string header, line, last;
  std::getline(history, header);
  while (std::getline(history, line)) last = line;
  std::vector<std::string> names, values;
  for (auto* pair : {&header, &last}) {
    std::stringstream ss(*pair);
    for (std::string cell; std::getline(ss, cell, ',');)
      (pair == &header ? names : values).push_back(cell);
  }
  ASSERT_EQ(names.size(), values.size());
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return std::stod(values[i]);
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  EXPECT_EQ(values[2], "settle");
  EXPECT_NEAR(column("elastic_energy_J"), 0.5 * column("gravity_work_J"),
              1e-2 * column("gravity_work_J"));
  EXPECT_LT(column("kinetic_energy_J"), 1e-6 * column("gravity_work_J"));
  EXPECT_LT(std::abs(column("energy_residual_ratio")), 1e-2);
  // summary.json's budget is the same last level (CSV: 12 significant digits).
  const auto summary = nlohmann::json::parse(std::ifstream(dir / "out" / "summary.json"));
  for (const char* key : {"gravity_work", "elastic", "damping_dissipation"}) {
    const double v = summary["energy_J"][key].get<double>();
    EXPECT_NEAR(v, column(std::string(key) + (key[0] == 'e' ? "_energy_J" : "_J")), 1e-10 * v)
        << key;
  }

  const double weight = 2500.0 * 9.81 * (0.2 * 0.3 * 0.1 + 0.1 * 0.1 * 0.05);
  const std::string python =
      std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string command = "VOLUMES=0.1,0.006,0.0005 " + python +
                              " '" BLOCKDEM_SOURCE_DIR "/tests/unit/io/read_vtk_output.py' '" +
                              (dir / "out").string() + "' 3 " + std::to_string(weight) + " 200";
  // No skip: without python3-vtk9 the script fails, and so does this test.
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << command;
}

}  // namespace
}  // namespace blockdem
