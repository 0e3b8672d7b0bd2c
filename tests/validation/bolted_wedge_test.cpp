// The roof wedge of scenarios/examples/roof_wedge_bolted.toml (Goodman & Shi 1985's tetrahedral
// key block, 6.25 m^3, with joint friction 40 degrees: by block theory its factor of safety is
// 0.75, tests/validation/stability_key_block_test.cpp's value at 55 degrees scaled by
// tan 40 / tan 55). Unsupported, the excavation lets it fall (it moves more than the key-block
// threshold, 0.1 V^(1/3) = 0.18 m); with the example's three grouted bolts, installed by the
// excavation stage, it is held (no key block) and every bolt stays intact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "stability_support.hpp"
#include "support/cli_runner.hpp"
#include "support/input_error.hpp"
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
  Scenario sc = example();
  sc.output.history_bolts = {"B2"};
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
  // time_history.csv's last row (the stage end) has B2's largest tendon force, as bolts.csv.
  std::ifstream history(out / "time_history.csv");
  std::string header, last;
  std::getline(history, header);
  while (std::getline(history, line)) last = line;
  const auto column = [](const std::string& row, std::size_t k) {
    std::size_t at = 0;
    for (std::size_t j = 0; j < k; ++j) at = row.find(',', at) + 1;
    return row.substr(at, row.find(',', at) - at);
  };
  std::size_t k = 0;
  while (column(header, k) != "B2_axial_force_N" && k < 100) ++k;
  ASSERT_LT(k, 100u) << header;
  EXPECT_EQ(column(header, k + 1), "B2_shear_force_N");
  EXPECT_NEAR(std::stod(column(last, k)), largest, 1e-9 * largest);
  std::printf("bolted roof wedge: largest tendon force %.4g N\n", largest);
}

// The bolts' loads are summed serially in bolt order: one thread and three give the same bytes.
TEST(BoltedWedge, BoltsCsvIsTheSameBytesForOneAndThreeThreads) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  std::string text[2];
  for (int k = 0; k < 2; ++k) {
    Scenario sc = example();
    sc.settings.threads = k == 0 ? 1 : 3;
    const auto out = test::run_folder("bolted_wedge_threads_" + std::to_string(k));
    std::filesystem::remove_all(out);
    ASSERT_EQ(run_scenario(sc, out).status, RunStatus::completed);
    std::ifstream in(out / "bolts.csv");
    text[k].assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  EXPECT_FALSE(text[0].empty());
  EXPECT_EQ(text[0], text[1]);
}

// The same wedge bolted by a pattern on the opening: on the roof (the wedge's base, the triangle
// (2.5, 0), (5, ±1.5) of z = 0) a 1 m lattice at half-metre offsets keeps (4.5, ±0.5) only
// ((3.5, ±0.5) lie within a tenth of the spacing of the triangle's edges), each bolt vertical
// into the wedge; they hold it.
TEST(BoltedWedge, PatternOnTheOpeningPutsBoltsNormalToItsFacesAndHoldsTheWedge) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  const std::filesystem::path file = std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" /
                                     "examples" / "roof_wedge_bolted.toml";
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = text.substr(0, text.find("[[bolts]]"));
  text +=
      "[[bolt_patterns]]\nname = \"roof\"\nexcavation = \"opening\"\nspacing = [1.0, 1.0]\n"
      "length = 3.0\naxial_stiffness = 3.33e7\nyield_force = 2e5\nbond_stiffness = 1.12e8\n"
      "bond_strength = 1.75e5\nshear_stiffness = 1e8\nshear_capacity = 1e5\n"
      "install_stage = \"excavate and bolt\"\n";
  const Scenario sc = parse_scenario(text, "pattern.toml");
  std::vector<Eigen::Vector3d> roof;
  for (const BoltSpec& b : sc.stages[1].bolts) {
    // Every bolt normal to a face of the opening, from it into the rock.
    EXPECT_NEAR(b.direction.norm(), 1.0, 1e-12);
    if (b.direction.z() > 1.0 - 1e-12) roof.push_back(b.start);
  }
  ASSERT_EQ(roof.size(), 2u);
  std::sort(roof.begin(), roof.end(), [](const auto& p, const auto& q) { return p.y() < q.y(); });
  EXPECT_LT((roof[0] - Eigen::Vector3d(4.5, -0.5, 0.0)).norm(), 1e-9);
  EXPECT_LT((roof[1] - Eigen::Vector3d(4.5, 0.5, 0.0)).norm(), 1e-9);
  const auto out = test::run_folder("bolted_wedge_pattern");
  std::filesystem::remove_all(out);
  const RunResult r = run_scenario(sc, out);
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  EXPECT_TRUE(r.summary.at("stages").at(1).at("key_blocks").empty());
  std::printf("pattern on the opening: %zu bolts, %zu in the roof\n", sc.stages[1].bolts.size(),
              roof.size());
}

// The bolted tunnel example's pattern (docs/support.md quotes these counts): 135 collars at
// 0.75 m on the faces the tunnel shares with the rock, 26 of whose bolts cross no joint or
// leave the model.
TEST(BoltedWedge, TunnelPatternPutsInTheBoltsTheDocsCount) {
  const std::filesystem::path file =
      std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" / "examples" / "tunnel_bolted.toml";
  const Scenario sc = load_scenario(file.string());
  std::size_t bolts = 0;
  for (const Stage& st : sc.stages) bolts += st.bolts.size();
  EXPECT_EQ(bolts, 109u);
  ASSERT_FALSE(sc.warnings.empty());
  EXPECT_NE(sc.warnings.back().find("26 of 135 bolts"), std::string::npos) << sc.warnings.back();
}

// Restart files do not hold bolts yet: asking for checkpoints is refused before anything is
// written, rather than losing the bolts on a restart.
TEST(BoltedWedge, CheckpointsAreRefusedWithBolts) {
  const std::filesystem::path file = std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" /
                                     "examples" / "roof_wedge_bolted.toml";
  const auto out = test::run_folder("bolted_wedge_checkpoint");
  std::filesystem::remove_all(out);
  const auto r = test::run_cli("run '" + file.string() + "' --out '" + out.string() +
                               "' --quiet --no-figures --checkpoint-every 100");
  test::expect_input_error(r, out, {"roof_wedge_bolted.toml", "checkpoints", "bolts"});
}

}  // namespace
}  // namespace bolted_wedge_test
}  // namespace blockdem
