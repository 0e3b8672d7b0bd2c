// The roof wedge of scenarios/examples/roof_wedge_bolted.toml (Goodman & Shi 1985's tetrahedral
// key block, 6.25 m^3, with joint friction 40 degrees: by block theory its factor of safety is
// 0.75, tests/validation/stability_key_block_test.cpp's value at 55 degrees scaled by
// tan 40 / tan 55). Unsupported, the excavation lets it fall (it moves more than the key-block
// threshold, 0.1 V^(1/3) = 0.18 m); with the example's three grouted bolts, installed by the
// excavation stage, it is held (no key block) and every bolt stays intact. Below: the wedge at
// 15 degrees held by three bolts along its line of sliding and falling with two, and where the
// couple of off-centre bolts holds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "stability_support.hpp"
#include "support/cli_runner.hpp"
#include "support/sanitized_run.hpp"

namespace blockdem {
namespace bolted_wedge_test {
namespace {

Scenario example() {
  const std::filesystem::path file = std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" /
                                     "examples" / "roof_wedge_bolted.toml";
  return load_scenario(file.string());
}

// The example's text up to its [[bolts]]: the scene and stages, no bolts.
std::string example_without_bolts() {
  const std::filesystem::path file = std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" /
                                     "examples" / "roof_wedge_bolted.toml";
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.substr(0, text.find("[[bolts]]"));
}

// The rows of a CSV file after its header, split at commas.
std::vector<std::vector<std::string>> csv_rows(const std::filesystem::path& csv) {
  std::vector<std::vector<std::string>> table;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    table.push_back(cells);
  }
  return table;
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
  double largest = 0.0, largest_b2 = 0.0;
  std::getline(csv, line);
  EXPECT_EQ(line, "stage,bolt,segment,block,from_m,to_m,axial_force_N,shear_force_N,state");
  while (std::getline(csv, line)) {
    ++rows;
    std::size_t at = 0;
    for (int k = 0; k < 6; ++k) at = line.find(',', at) + 1;
    const double axial = std::stod(line.substr(at));
    largest = std::max(largest, axial);
    if (line.find(",B2,") != std::string::npos) largest_b2 = std::max(largest_b2, axial);
  }
  EXPECT_EQ(rows, 6);
  EXPECT_GT(largest, 0.0);
  // time_history.csv's last row (the stage end) has B2's largest tendon force, as bolts.csv (B2
  // and B3 are placed alike: which of the two carries the very largest is round-off's choice).
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
  EXPECT_NEAR(std::stod(column(last, k)), largest_b2, 1e-9 * largest_b2);
  EXPECT_NEAR(largest_b2, largest, 1e-4 * largest);
  std::printf("bolted roof wedge: largest tendon force %.4g N\n", largest);
}

// The bolts' loads are summed serially in bolt order: one thread and three give the same bytes
// (bolts.csv, and blocks.csv, which their loads move). The roof wedge's three bolts are solved on
// one thread; the 73 bolts of scenarios/examples/slope_bolted.toml, over the first 300 steps of
// the stage that cuts the slope and installs them, side by side on the threads.
TEST(BoltedWedge, BoltsCsvIsTheSameBytesForOneAndThreeThreads) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  const auto slope = [] {
    Scenario sc = load_scenario((std::filesystem::path(BLOCKDEM_SOURCE_DIR) / "scenarios" /
                                 "examples" / "slope_bolted.toml")
                                    .string());
    sc.stages[1].kind = Stage::Kind::steps;
    sc.stages[1].steps = 300;
    return sc;
  };
  for (const char* scene : {"wedge", "slope"}) {
    std::string bolts[2], blocks[2];
    for (int k = 0; k < 2; ++k) {
      Scenario sc = scene == std::string("wedge") ? example() : slope();
      sc.settings.threads = k == 0 ? 1 : 3;
      const auto out = test::run_folder("bolted_" + std::string(scene) + std::to_string(k));
      std::filesystem::remove_all(out);
      const RunResult r = run_scenario(sc, out);
      ASSERT_EQ(r.status, RunStatus::completed) << r.message;
      if (scene == std::string("slope")) {
        EXPECT_EQ(r.summary.at("bolts").at("installed").get<int>(), 73);
      }
      for (auto [file, text] :
           {std::pair{"bolts.csv", &bolts[k]}, std::pair{"blocks.csv", &blocks[k]}}) {
        std::ifstream in(out / file);
        text->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
    }
    EXPECT_FALSE(bolts[0].empty()) << scene;
    EXPECT_EQ(bolts[0], bolts[1]) << scene;
    EXPECT_EQ(blocks[0], blocks[1]) << scene;
  }
}

// The same wedge bolted by a pattern on the opening: on the roof (the wedge's base, the triangle
// (2.5, 0), (5, ±1.5) of z = 0) a 1 m lattice at half-metre offsets keeps (4.5, ±0.5) only
// ((3.5, ±0.5) lie within a tenth of the spacing of the triangle's edges), each bolt vertical
// into the wedge; they hold it.
TEST(BoltedWedge, PatternOnTheOpeningPutsBoltsNormalToItsFacesAndHoldsTheWedge) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  std::string text = example_without_bolts();
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

// The same wedge with friction 15 degrees, held by point-anchored bolts along its line of sliding
// and falling with one fewer. Block theory (Goodman & Shi 1985, ch. 8; Hoek & Bray, Rock Slope
// Engineering, ch. 8): it slides on J2 and J3 down their line of intersection s, plunging 63.4
// degrees east, and leaves J1. With g the unit gravity and n2, n3 its outward normals there,
// g - (g.s) s = mu2 n2 + mu3 n3 gives the normal forces N_i = mu_i W; the driving force is
// S = W (g.s), the friction R = (N2 + N3) tan(phi), F = R / S. A bolt force T along -s adds
// nothing normal to J2 or J3 (s lies in both), so F(T) = R / (S - T): F = 1 needs T1 = S - R,
// F = 1.5 needs T1.5 = S - R / 1.5. Every bolt here runs along -s from the roof, parallel to J2
// and J3 (it crosses J1 only, 1 m into the rock above it), so the wedge's slide stretches each
// bolt by exactly its travel without turning it. The bolts sit on the roof at x = 3.75 m, where
// the line through the wedge's centroid (3.125, 0, 1.25) along s meets it, at y = 0 and +-0.4 m:
// three bolts, or the outer two, have their resultant on that line, so they put no couple on the
// wedge (a couple can turn it onto J1, whose friction then helps: docs/support.md). Each yields
// at C = 45 kN: 3 C >= T1.5 holds the wedge; 2 C < T1, and friction cannot make up the rest
// (the bolts along s leave N2 and N3 as they are, J1 opens, so R is all the joints can give and
// 2 C + R < S): the two yield, stretch to their rupture strain and break, and the wedge falls.
// The excavation relaxes over 60000 steps, so the wedge creeps to rest as the bolts take the
// load, friction at its limit: three bolts then carry T1 between them. Friction cannot give more
// than R, so the bolts carry at least T1 (to 1e-3); the wedge stops with its friction a little
// below the limit (the relaxation ends with the wedge still moving), within 2 % of T1 with
// face_integrated contacts and 5 % with boon2012's point contacts (91 % of the limit there).
struct WedgeBolts {
  double weight = 0.0, driving = 0.0, friction = 0.0;  // W, S, R (N)
};

constexpr double kWedgePhiDeg = 15.0, kWedgeBoltYield = 4.5e4;

WedgeBolts wedge_by_hand() {
  const auto normal = [](double dip_deg, double direction_deg) {
    const double d = dip_deg * std::numbers::pi / 180.0,
                 a = direction_deg * std::numbers::pi / 180.0;
    return Eigen::Vector3d(std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d));
  };
  // The wedge lies on the upper side of J2 and J3 (their normals point up into it): its outward
  // normals there are the joints' normals reversed.
  const Eigen::Vector3d n2 = -normal(75.574, 149.036), n3 = -normal(75.574, 30.964);
  Eigen::Vector3d s = n2.cross(n3).normalized();
  if (s.z() > 0.0) s = -s;
  const Eigen::Vector3d g(0.0, 0.0, -1.0);
  const Eigen::Vector3d across = g - g.dot(s) * s;
  Eigen::Matrix2d gram;
  gram << 1.0, n2.dot(n3), n2.dot(n3), 1.0;
  const Eigen::Vector2d mu = gram.inverse() * Eigen::Vector2d(across.dot(n2), across.dot(n3));
  // The tetrahedron of apex (0, 0, 5) on the roof's triangle (2.5, 0), (5, +-1.5): V = A h / 3.
  const double volume = (0.5 * 2.5 * 3.0) * 5.0 / 3.0;
  WedgeBolts w;
  w.weight = 2700.0 * 9.81 * volume;
  w.driving = w.weight * g.dot(s);
  w.friction = (mu(0) + mu(1)) * w.weight * std::tan(kWedgePhiDeg * std::numbers::pi / 180.0);
  return w;
}

// The example with friction 15 degrees and a bolt at each of `ys` (m) on the roof's x = 3.75.
Scenario wedge_with_bolts(const std::vector<double>& ys) {
  std::string text = example_without_bolts();
  const std::string from = "friction_deg = 40";
  text.replace(text.find(from), from.size(), "friction_deg = 15");
  std::ostringstream bolts;
  bolts.precision(17);
  const double into_wedge = 1.25 * std::sqrt(5.0);  // (3.75, y, 0) to J1 at (2.5, y, 2.5)
  for (std::size_t k = 0; k < ys.size(); ++k) {
    bolts << "[[bolts]]\nname = \"W" << k + 1 << "\"\nstart = [3.75, " << ys[k]
          << ", 0]\ndirection = [" << -1.0 / std::sqrt(5.0) << ", 0, " << 2.0 / std::sqrt(5.0)
          << "]\nlength = " << into_wedge + 1.0
          << "\naxial_stiffness = 2.6e7\nyield_force = " << kWedgeBoltYield
          << "\nrupture_strain = 0.02\ninstall_stage = \"excavate and bolt\"\n";
  }
  Scenario sc = parse_scenario(text + bolts.str(), "roof_wedge_bolts_on_its_line.toml");
  sc.stages[1].relax_steps = 60000;
  return sc;
}

class WedgeBoltModes : public ::testing::TestWithParam<ContactMode> {};

TEST_P(WedgeBoltModes, BoltsAlongTheSlideHoldTheWedgeAndOneFewerLetItFall) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  const WedgeBolts hand = wedge_by_hand();
  const double t1 = hand.driving - hand.friction, t15 = hand.driving - hand.friction / 1.5;
  // The design: three bolts bring F to 1.5 or more, two fall short of F = 1.
  ASSERT_GE(3.0 * kWedgeBoltYield, t15);
  ASSERT_LT(2.0 * kWedgeBoltYield, t1);
  const std::string mode = to_string(GetParam());
  // Three bolts: held, no bolt ruptured, and at rest they carry T1 between them.
  {
    Scenario sc = wedge_with_bolts({-0.4, 0.0, 0.4});
    sc.settings.contact_mode = GetParam();
    const auto out = test::run_folder("wedge_three_on_its_line_" + mode);
    std::filesystem::remove_all(out);
    const RunResult r = run_scenario(sc, out);
    ASSERT_EQ(r.status, RunStatus::completed) << r.message;
    const nlohmann::json& stage = r.summary.at("stages").at(1);
    EXPECT_TRUE(stage.at("key_blocks").empty()) << stage.at("key_blocks").dump();
    // Block theory's entry for the wedge agrees with the hand calculation above.
    const nlohmann::json* theory = nullptr;
    for (const auto& b : stage.at("removable_blocks")) {
      if (std::abs(b.at("volume_m3").get<double>() - 6.25) < 1e-2) theory = &b;
    }
    ASSERT_NE(theory, nullptr) << stage.at("removable_blocks").dump();
    EXPECT_EQ(theory->at("mode").get<std::string>(), "sliding_two");
    const double w = theory->at("weight_N").get<double>();
    EXPECT_NEAR(w, hand.weight, 1e-3 * hand.weight);  // the dips as given: V = 6.2505 m^3
    EXPECT_NEAR(theory->at("factor_of_safety").get<double>(), hand.friction / hand.driving, 1e-3);
    EXPECT_NEAR(theory->at("support_force_N").get<double>(), t15, 1e-3 * t15);
    EXPECT_EQ(r.summary.at("bolts").at("ruptured").get<int>(), 0);
    double total = 0.0;
    for (const auto& cells : csv_rows(out / "bolts.csv")) {
      ASSERT_EQ(cells.size(), 9u);
      if (cells[2] == "1") total += std::stod(cells[6]);  // each bolt's segment in the wedge
    }
    EXPECT_GE(total, (1.0 - 1e-3) * t1);
    const double tolerance = GetParam() == ContactMode::face_integrated ? 0.02 : 0.05;
    EXPECT_NEAR(total, t1, tolerance * t1);
    std::printf(
        "wedge (%s), three bolts along its slide: W %.6g N (hand %.6g), F %.4f (hand %.4f), "
        "T1.5 %.6g N (hand %.6g); held, bolts' total %.6g N against T1 = S - R = %.6g N (%.2e)\n",
        mode.c_str(), w, hand.weight, theory->at("factor_of_safety").get<double>(),
        hand.friction / hand.driving, theory->at("support_force_N").get<double>(), t15, total, t1,
        total / t1 - 1.0);
  }
  // Two bolts: they yield, rupture, and the wedge falls.
  Scenario sc = wedge_with_bolts({-0.4, 0.4});
  sc.settings.contact_mode = GetParam();
  sc.stages[1].max_steps = 150000;
  const auto out = test::run_folder("wedge_two_on_its_line_" + mode);
  std::filesystem::remove_all(out);
  const RunResult r = run_scenario(sc, out);
  EXPECT_NE(r.status, RunStatus::completed);
  EXPECT_EQ(r.summary.at("bolts").at("installed").get<int>(), 2);
  EXPECT_EQ(r.summary.at("bolts").at("ruptured").get<int>(), 2);
  const nlohmann::json* wedge = wedge_entry(r.summary.at("stages").at(1).at("key_blocks"));
  ASSERT_NE(wedge, nullptr) << r.summary.at("stages").at(1).at("key_blocks").dump();
  EXPECT_GT(wedge->at("displacement_m").get<double>(), 0.18);  // 0.1 V^(1/3)
  std::printf("wedge (%s), two bolts: %d ruptured, the wedge %.3g m out of place\n", mode.c_str(),
              r.summary.at("bolts").at("ruptured").get<int>(),
              wedge->at("displacement_m").get<double>());
}

INSTANTIATE_TEST_SUITE_P(BoltedWedge, WedgeBoltModes,
                         ::testing::Values(ContactMode::face_integrated, ContactMode::boon2012),
                         [](const ::testing::TestParamInfo<ContactMode>& mode) {
                           return std::string(to_string(mode.param));
                         });

// Where a bolt's couple matters. The example's wedge (friction 40 degrees, F = 0.7531) with two
// vertical point-anchored bolts, 3 m long, each yielding at 66 kN (together 0.797 W). A vertical
// bolt force T only lightens the wedge: with c = 0 every normal force, the friction and the
// driving force scale by (W - T) / W, so F stays 0.7531 for any T < W, and block theory's support
// force for a vertical bolt and F = 1 is W itself (analysis/block_theory.hpp, support_force).
// On the vertical line through the centroid, (3.125, +-0.3), the bolts put no couple on the
// wedge and the run agrees: they yield, rupture, and the wedge slides on. Off to the east, at
// (4.5, +-0.6) under J1, the same two bolts hold it: their couple (about the north-south axis)
// turns the wedge by some 0.01 degrees and presses it onto J2 and J3 harder than its weight less
// the bolts' pull would (block theory's N on each, 0.4014 (W - T), against nearly twice that
// in the run), and their friction holds the rest. Block theory, a translation only, cannot see
// this: it is on the safe side.
TEST(BoltedWedge, OffCentreBoltsHoldTheWedgeByTheirCoupleWhereCentredOnesFail) {
  if (test::sanitized_run()) GTEST_SKIP() << "minutes under the sanitizers";
  const auto with_bolts = [](double x, double y) {
    std::ostringstream bolts;
    for (int k = 0; k < 2; ++k) {
      bolts
          << "[[bolts]]\nname = \"B" << k + 1 << "\"\nstart = [" << x << ", " << (k ? y : -y)
          << ", 0]\ndirection = [0, 0, 1]\nlength = 3.0\naxial_stiffness = 2.6e7\n"
          << "yield_force = 6.6e4\nrupture_strain = 0.02\ninstall_stage = \"excavate and bolt\"\n";
    }
    return parse_scenario(example_without_bolts() + bolts.str(),
                          "roof_wedge_two_vertical_bolts.toml");
  };
  // Centred: no couple; they rupture and the wedge moves on (the stage does not converge).
  {
    const auto out = test::run_folder("wedge_vertical_centred");
    std::filesystem::remove_all(out);
    const RunResult r = run_scenario(with_bolts(3.125, 0.3), out);
    EXPECT_NE(r.status, RunStatus::completed);
    EXPECT_EQ(r.summary.at("bolts").at("ruptured").get<int>(), 2);
  }
  // Off-centre: held.
  const auto out = test::run_folder("wedge_vertical_off_centre");
  std::filesystem::remove_all(out);
  const RunResult r = run_scenario(with_bolts(4.5, 0.6), out);
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  const nlohmann::json& stage = r.summary.at("stages").at(1);
  EXPECT_TRUE(stage.at("key_blocks").empty());
  EXPECT_EQ(r.summary.at("bolts").at("ruptured").get<int>(), 0);
  const nlohmann::json* theory = nullptr;
  for (const auto& b : stage.at("removable_blocks")) {
    if (std::abs(b.at("volume_m3").get<double>() - 6.25) < 1e-2) theory = &b;
  }
  ASSERT_NE(theory, nullptr);
  const std::string wedge = theory->at("block").get<std::string>();
  const double w = theory->at("weight_N").get<double>();
  // The bolts' pull (bolts.csv) and the normal forces on the wedge's contacts (contacts.csv).
  double pull = 0.0;
  for (const auto& row : csv_rows(out / "bolts.csv")) {
    if (row.at(2) == "1") pull += std::stod(row.at(6));
  }
  std::vector<double> normal;
  for (const auto& row : csv_rows(out / "contacts.csv")) {
    if (row.at(0) == "1" && (row.at(2) == wedge || row.at(3) == wedge))
      normal.push_back(std::stod(row.at(13)));
  }
  std::sort(normal.rbegin(), normal.rend());
  ASSERT_GE(normal.size(), 2u);
  // Block theory's normal force on each of J2 and J3 under the net load W - T.
  const double mu = theory->at("planes").at(0).at("normal_force_N").get<double>() / w;
  const double lightened = mu * (w - pull);
  EXPECT_LT(pull, w);
  EXPECT_GT(normal[1], 1.5 * lightened);
  std::printf(
      "two vertical bolts off the centroid's line: held, the bolts pull %.4g N (%.3f W); normal "
      "forces on J2 and J3 %.4g and %.4g N against %.4g N each by block theory under W - T\n",
      pull, pull / w, normal[0], normal[1], lightened);
}

}  // namespace
}  // namespace bolted_wedge_test
}  // namespace blockdem
