// The roof wedge of scenarios/examples/roof_wedge_bolted.toml (Goodman & Shi 1985's tetrahedral
// key block, 6.25 m^3, with joint friction 40 degrees: by block theory its factor of safety is
// 0.75, tests/validation/stability_key_block_test.cpp's value at 55 degrees scaled by
// tan 40 / tan 55). Unsupported, the excavation lets it fall (it moves more than the key-block
// threshold, 0.1 V^(1/3) = 0.18 m); with the example's three grouted bolts, installed by the
// excavation stage, it is held (no key block) and every bolt stays intact.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "stability_support.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem {
namespace bolted_wedge_test {
namespace {

Scenario example() {
  const std::filesystem::path file = std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" /
                                     "examples" / "roof_wedge_bolted.toml";
  return load_scenario(file.string());
}

// The wedge: the key block whose centroid started at the tetrahedron's, (3.125, 0, 1.25).
const nlohmann::json* wedge_entry(const nlohmann::json& key_blocks) {
  for (const auto& k : key_blocks) {
    const auto& c = k.at("centroid_at_start_m");
    const Eigen::Vector3d at(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
    if ((at - Eigen::Vector3d(3.125, 0.0, 1.25)).norm() < 0.5) return &k;
  }
  return nullptr;
}

TEST(BoltedWedge, ThreeBoltsHoldTheKeyBlockThatFallsWithout) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  // Unsupported: the wedge leaves the roof (the stage is cut short: it would not converge).
  {
    Scenario sc = example();
    for (Stage& st : sc.stages) st.bolts.clear();
    sc.stages[1].max_steps = 100000;
    const auto out = test::run_folder("bolted_wedge_none");
    std::filesystem::remove_all(out);
    const RunResult r = run_scenario(sc, out);
    EXPECT_NE(r.status, RunStatus::completed);
    const auto& keys = r.summary.at("stages").at(1).at("key_blocks");
    const nlohmann::json* wedge = wedge_entry(keys);
    ASSERT_NE(wedge, nullptr) << keys.dump();
    EXPECT_GT(wedge->at("displacement_m").get<double>(), 0.18);     // 0.1 V^(1/3)
    EXPECT_NEAR(wedge->at("volume_m3").get<double>(), 6.25, 1e-3);  // the joints as given: 6.2505
  }
  // Bolted: held, every bolt intact.
  const Scenario sc = example();
  const auto out = test::run_folder("bolted_wedge_three");
  std::filesystem::remove_all(out);
  const RunResult r = run_scenario(sc, out);
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  EXPECT_TRUE(r.summary.at("stages").at(1).at("key_blocks").empty());
  EXPECT_EQ(r.summary.at("bolts").at("installed").get<int>(), 3);
  EXPECT_EQ(r.summary.at("bolts").at("intact").get<int>(), 3);
  EXPECT_TRUE(std::filesystem::exists(out / "bolts.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "vtk" / "bolts_000000.vtu"));
  // bolts.csv: one row per bolt and segment (two segments each: the wedge, the rock above J1).
  std::ifstream csv(out / "bolts.csv");
  std::string line;
  int rows = 0;
  double largest = 0.0;
  std::getline(csv, line);
  EXPECT_EQ(line, "stage,bolt,segment,block,from_m,to_m,axial_force_N,shear_force_N,state");
  while (std::getline(csv, line)) {
    ++rows;
    std::size_t at = 0;
    for (int k = 0; k < 6; ++k) at = line.find(',', at) + 1;
    largest = std::max(largest, std::stod(line.substr(at)));
  }
  EXPECT_EQ(rows, 6);
  EXPECT_GT(largest, 0.0);
  std::printf("bolted roof wedge: largest tendon force %.4g N\n", largest);
}

}  // namespace
}  // namespace bolted_wedge_test
}  // namespace blockdem
