// The voussoir beams T2-1 and T3-full in mode face_integrated without the plane constraint
// (plane_motion = false): the joints' twisting resistance keeps the beam from buckling sideways up
// to 40 g, and thrust and midspan deflection match the plane-constrained runs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/voussoir/measures.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

// The paper's case file in mode face_integrated, with the plane constraint and twist as given.
RunResult run_variant(const std::string& id, bool plane_motion, bool twist) {
  const std::string path = std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/boon2015/" + id + ".toml";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string toml = text.str();
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = toml.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    toml.replace(at, from.size(), to);
  };
  replace("contact_mode = \"boon2012\"",
          std::string("contact_mode = \"face_integrated\"\ntwist = ") + (twist ? "true" : "false"));
  replace("[voussoir]\n",
          std::string("[voussoir]\nplane_motion = ") + (plane_motion ? "true" : "false") + "\n");
  Scenario sc = parse_scenario(toml, path);
  sc.output.vtk = false;
  const auto out = test::temp_path("voussoir3d_" + id + (plane_motion ? "_plane" : "_3d") +
                                   (twist ? "" : "_notwist"));
  std::filesystem::remove_all(out);
  return run_scenario(sc, out);
}

class Voussoir3d : public ::testing::TestWithParam<std::string> {};

// Reference: the plane-constrained run of the same case; tolerance 1% (measured at most 3e-6 for
// T2-1 and 3e-3 for T3-full, whose partly open exponential joints slip fully: the deflection
// differs most; 4.1e-3 with the full-slip code before the exponential law's closed radial form).
// A beam that buckles sideways stops as "collapsed" before 40 g. Prints the 40 g figures and the
// largest difference.
TEST_P(Voussoir3d, NoSidewaysBucklingAndThePlaneResultsWithoutTheConstraint) {
  const RunResult plane = run_variant(GetParam(), true, true);
  const RunResult free = run_variant(GetParam(), false, true);
  ASSERT_EQ(plane.status, RunStatus::completed) << plane.message;
  ASSERT_EQ(free.status, RunStatus::completed) << free.message;
  ASSERT_EQ(voussoir_levels(free).size(), voussoir_levels(plane).size());
  EXPECT_DOUBLE_EQ(voussoir_levels(free).back().g_level, 40.0);
  double largest = 0.0;  // the largest relative difference over the levels
  for (std::size_t k = 1; k < voussoir_levels(plane).size(); ++k) {
    const VoussoirLevel& p = voussoir_levels(plane)[k];
    const VoussoirLevel& f = voussoir_levels(free)[k];
    SCOPED_TRACE("g = " + std::to_string(p.g_level));
    EXPECT_NEAR(f.thrust, p.thrust, 0.01 * p.thrust);
    EXPECT_NEAR(f.midspan_deflection, p.midspan_deflection, 0.01 * p.midspan_deflection);
    largest = std::max(
        {largest, std::abs(f.thrust - p.thrust) / p.thrust,
         std::abs(f.midspan_deflection - p.midspan_deflection) / std::abs(p.midspan_deflection)});
  }
  const VoussoirLevel& p = voussoir_levels(plane).back();
  const VoussoirLevel& f = voussoir_levels(free).back();
  std::printf(
      "%s at %.0f g: thrust %.6f N (plane) / %.6f N (3D), midspan deflection %.6f / %.6f mm; "
      "largest relative difference over the levels %.2g\n",
      GetParam().c_str(), p.g_level, p.thrust, f.thrust, 1e3 * p.midspan_deflection,
      1e3 * f.midspan_deflection, largest);
}

std::string case_name(const ::testing::TestParamInfo<std::string>& p) {
  return p.param == "T2-1" ? "T2_1" : "T3_full";
}
INSTANTIATE_TEST_SUITE_P(Cases, Voussoir3d, ::testing::Values("T2-1", "T3-full"), case_name);

// The check can fail: without twist the unconstrained T2-1 beam collapses sideways before 40 g
// (measured: at 10 g, last stable level 5 g).
TEST(Voussoir3dControl, WithoutTwistTheUnconstrainedBeamBucklesSideways) {
  const RunResult r = run_variant("T2-1", false, false);
  EXPECT_EQ(r.status, RunStatus::collapsed) << r.message;
  ASSERT_FALSE(voussoir_levels(r).empty());
  EXPECT_LT(voussoir_levels(r).back().g_level, 40.0);
}

}  // namespace
}  // namespace blockdem
