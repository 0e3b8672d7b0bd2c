// Key blocks by block theory (run/removable_blocks.hpp, `blockdem keyblocks`) on the tetrahedral
// roof wedge of scenarios/examples/roof_wedge.toml (Goodman & Shi 1985, Block Theory and Its
// Application to Rock Engineering): the volume against the tetrahedron the three joints and the
// roof bound (1e-9 relative), the mode (sliding on J2 and J3), and the factor of safety against
// Hoek & Bray's symmetric wedge (Rock Slope Engineering, ch. 8: F = K tan(phi) / tan(psi_i),
// wedge factor K = sin(beta) / sin(xi / 2) with beta = 90 degrees for a wedge symmetric about
// the vertical through its line of intersection; xi the wedge's angle at that line, psi_i its
// plunge), within 1%. The CLI writes the same list, and refuses a scenario without an opening.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/numerics/units.hpp"
#include "blockdem/run/removable_blocks.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "support/cli_runner.hpp"
#include "support/dense_solves.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace key_block_theory_test {

const std::string kRoofWedge =
    std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/examples/roof_wedge.toml";

/// The plane dipping `dip` towards `dip_direction` through `p`, as (upward normal, offset).
std::pair<Eigen::Vector3d, double> joint(double dip_deg, double dip_direction_deg,
                                         const Eigen::Vector3d& p) {
  const double d = deg_to_rad(dip_deg), a = deg_to_rad(dip_direction_deg);
  const Eigen::Vector3d n(std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d));
  return {n, n.dot(p)};
}

/// The point on three planes.
Eigen::Vector3d meet(const std::pair<Eigen::Vector3d, double>& a,
                     const std::pair<Eigen::Vector3d, double>& b,
                     const std::pair<Eigen::Vector3d, double>& c) {
  Eigen::Matrix3d m;
  m << a.first.transpose(), b.first.transpose(), c.first.transpose();
  return test::solve_full_lu(m, Eigen::Vector3d(a.second, b.second, c.second));
}

/// The wedge as the example's joints cut it: apex, and the roof's corners on J2-J3, J1-J2, J1-J3.
struct Wedge {
  Eigen::Vector3d apex, toe, side_a, side_b;
};
Wedge wedge() {
  const Eigen::Vector3d apex(0, 0, 5);
  const auto j1 = joint(45, 90, apex), j2 = joint(75.574, 149.036, apex),
             j3 = joint(75.574, 30.964, apex);
  const std::pair<Eigen::Vector3d, double> roof{Eigen::Vector3d::UnitZ(), 0.0};
  return {apex, meet(j2, j3, roof), meet(j1, j2, roof), meet(j1, j3, roof)};
}

std::size_t excavation_stage(const Scenario& sc) {
  for (std::size_t s = 0; s < sc.stages.size(); ++s) {
    if (!sc.stages[s].remove.empty()) return s;
  }
  return sc.stages.size();
}

TEST(KeyBlockTheory, RoofWedgeVolumeModeAndFactorOfSafety) {
  const Scenario sc = load_scenario(kRoofWedge);
  const std::size_t stage = excavation_stage(sc);
  ASSERT_LT(stage, sc.stages.size());
  const nlohmann::json blocks = removable_blocks(sc, stage, 1.5);
  // The wedge is the one block the opening frees: the rock around it reaches the model's
  // boundary.
  ASSERT_EQ(blocks.size(), 1u) << blocks.dump(2);
  const nlohmann::json& b = blocks[0];

  // Volume: the tetrahedron's, 1e-9 relative.
  const Wedge w = wedge();
  const double volume =
      std::abs((w.toe - w.apex).dot((w.side_a - w.apex).cross(w.side_b - w.apex))) / 6.0;
  EXPECT_NEAR(b["volume_m3"].get<double>(), volume, 1e-9 * volume);
  EXPECT_NEAR(b["weight_N"].get<double>(), 2700.0 * 9.81 * volume, 1e-9 * 2700.0 * 9.81 * volume);

  // Mode: on J2 and J3.
  EXPECT_EQ(b["mode"], "sliding_two");
  ASSERT_EQ(b["planes"].size(), 2u);
  EXPECT_EQ(b["planes"][0]["joint_set"], "J2");
  EXPECT_EQ(b["planes"][1]["joint_set"], "J3");

  // Hoek & Bray's symmetric wedge from the corners alone: the line of intersection runs from
  // the apex to the toe; xi is the angle between the two faces across it.
  const Eigen::Vector3d line = (w.toe - w.apex).normalized();
  const double psi = std::asin(-line.z());
  auto across = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d v = p - w.apex;
    return (v - v.dot(line) * line).normalized();
  };
  const double xi = std::acos(across(w.side_a).dot(across(w.side_b)));
  const double expected = std::tan(deg_to_rad(55.0)) / (std::tan(psi) * std::sin(0.5 * xi));
  const double f = b["factor_of_safety"].get<double>();
  std::printf("roof wedge: V = %.12g m3 (tetrahedron %.12g), F = %.8g (Hoek & Bray %.8g)\n",
              b["volume_m3"].get<double>(), volume, f, expected);
  EXPECT_NEAR(f, expected, 0.01 * expected);
  EXPECT_NEAR(f, 1.2818, 0.01 * 1.2818);  // the example's quoted value
  // Its direction: down the line of intersection.
  const Eigen::Vector3d d(b["direction"][0].get<double>(), b["direction"][1].get<double>(),
                          b["direction"][2].get<double>());
  EXPECT_LT((d - line).norm(), 1e-6);

  // Support against the motion: F = R / (W sin(psi) - T) = 1.5 with R = F0 W sin(psi).
  const double weight = b["weight_N"].get<double>();
  const double t = b["support_force_N"].get<double>();
  const double driving = weight * std::sin(psi);
  EXPECT_NEAR(f * driving / (driving - t), 1.5, 1e-6);
}

TEST(KeyBlockTheory, CommandWritesTheListAndRefusesAScenarioWithoutAnOpening) {
  namespace fs = std::filesystem;
  const fs::path out = test::temp_path("keyblocks_cli");
  fs::remove_all(out);
  const auto r = test::run_cli("keyblocks '" + kRoofWedge + "' --out '" + out.string() +
                               "' --required-factor 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sliding_two"), std::string::npos) << r.out;
  std::ifstream in(out / "key_blocks.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["required_factor"].get<double>(), 2.0);
  const Scenario sc = load_scenario(kRoofWedge);
  const nlohmann::json direct = removable_blocks(sc, excavation_stage(sc), 2.0);
  EXPECT_EQ(j["key_blocks"], direct);
  fs::remove_all(out);

  // A scenario without an excavation stage: exit 2, the file and key named, nothing written.
  const std::string bad =
      std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/examples/planar_sliding.toml";
  const auto e = test::run_cli("keyblocks '" + bad + "' --out '" + out.string() + "'");
  EXPECT_EQ(e.exit_code, 2) << e.err;
  EXPECT_NE(e.err.find(bad), std::string::npos) << e.err;
  EXPECT_NE(e.err.find("stages"), std::string::npos) << e.err;
  EXPECT_FALSE(fs::exists(out));
  // A required factor that is not a positive number: exit 2, nothing written.
  const auto f = test::run_cli("keyblocks '" + kRoofWedge + "' --out '" + out.string() +
                               "' --required-factor -1");
  EXPECT_EQ(f.exit_code, 2) << f.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace key_block_theory_test
}  // namespace blockdem
