// The voussoir beam of Boon, Houlsby & Utili (2015), every case of Tables 2 and 3 as shipped in
// scenarios/boon2015: statics (H z = W S / 8 within 1% at every level), symmetry of the
// symmetric beam (1e-5 relative; 1e-4 with the continuously-yielding law, see below), the preload
// (within 1% of 60 N), and the ratios of midspan deflections implied by the paper's Table 3 (within
// 5%).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/scene_builders.hpp"
#include "blockdem/studies/boon2015/cases.hpp"
#include "blockdem/voussoir/measures.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

RunResult run_case(const std::string& id) {
  Scenario sc =
      load_scenario(std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/boon2015/" + id + ".toml");
  sc.output.vtk = false;
  const auto out = test::temp_path("voussoir_" + id);
  std::filesystem::remove_all(out);
  return run_scenario(sc, out);
}

// The statics, the symmetry and the preload of case `id`'s run `r`.
void expect_statics_symmetry_and_preload(const std::string& id, const RunResult& r) {
  ASSERT_EQ(r.status, RunStatus::completed) << r.message;
  double g_max = 0;
  for (const auto& c : boon2015_cases()) {
    if (c.id == id) g_max = c.g_max;
  }
  ASSERT_FALSE(voussoir_levels(r).empty());
  EXPECT_DOUBLE_EQ(voussoir_levels(r).back().g_level, g_max);

  // Preload: both abutments push with 60 N within 1%.
  const VoussoirLevel& pre = voussoir_levels(r).front();
  EXPECT_NEAR(pre.thrust, 60.0, 0.6);
  EXPECT_NEAR(pre.thrust_left, 60.0, 0.6);

  // The continuously-yielding law has no elastic range at the start (mu(0) = 0, eq. 8): every
  // joint slips from the first increment, the split of the beam's weight between the abutments
  // is path-dependent, and round-off differences between mirrored force sums are not damped but
  // carried along. Measured asymmetry ~1e-5. The elastic-shear cases measured 1.4e-6 at most
  // and reversing the order of one sum in the analytic centre alone gives 6.5e-6: round-off
  // amplified by the relaxation, not a modelling asymmetry. Tolerance 1e-5.
  const bool plastic = id.rfind("T3-", 0) == 0 && id != "T3-half-old";
  const double sym = plastic ? 1e-4 : 1e-5;
  for (const VoussoirLevel& lv : voussoir_levels(r)) {
    SCOPED_TRACE("g = " + std::to_string(lv.g_level));
    // Statics of the half span.
    ASSERT_TRUE(std::isfinite(lv.equilibrium_residual));
    EXPECT_LT(lv.equilibrium_residual, 0.01);
    // Symmetry: thrust points mirror about the midspan joint, the profile about midspan.
    const auto& j = lv.joints;
    const std::size_t n = j.size();
    const double x_mid = j[n / 2].x;
    const double depth = 0.046;
    for (std::size_t k = 0; k < n / 2; ++k) {
      EXPECT_NEAR(j[k].x + j[n - 1 - k].x, 2 * x_mid, sym * 0.276);
      EXPECT_NEAR(j[k].z, j[n - 1 - k].z, sym * depth);
      EXPECT_NEAR(j[k].normal_force, j[n - 1 - k].normal_force, sym * j[k].normal_force);
    }
    double scale = 0.0, turn = 0.0;
    for (const auto& b : lv.blocks) {
      scale = std::max(scale, std::abs(b.deflection));
      turn = std::max(turn, std::abs(b.rotation));
    }
    const std::size_t m = lv.blocks.size();
    for (std::size_t k = 0; k < m / 2; ++k) {
      EXPECT_NEAR(lv.blocks[k].deflection, lv.blocks[m - 1 - k].deflection, sym * scale + 1e-15);
      // Rotations are differences of nearly equal orientations: 10 sym of the largest.
      EXPECT_NEAR(lv.blocks[k].rotation, -lv.blocks[m - 1 - k].rotation, 10 * sym * turn + 1e-15);
    }
    EXPECT_GE(lv.midspan_deflection, -1e-12);
  }
}

class VoussoirCase : public ::testing::TestWithParam<std::string> {};

TEST_P(VoussoirCase, StaticsSymmetryAndPreload) {
  expect_statics_symmetry_and_preload(GetParam(), run_case(GetParam()));
}

// The cases of Table 3 but T2-2 are checked by VoussoirPaper.Table3DeflectionRatios, which runs
// them. T2-2 is checked here as well, a short run that the sanitized tests keep.
INSTANTIATE_TEST_SUITE_P(Boon2015, VoussoirCase, ::testing::Values("T2-1", "T2-2", "T2-3", "F8"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string s = p.param;
                           for (char& c : s) c = (c == '-') ? '_' : c;
                           return s;
                         });

// Table 3 implies that the new laws predict (1 + new)/(1 + old) times the midspan deflection of
// the old ones: 2.13 for the full beam (mean over three tests) and 2.125 for the half beam. The
// three T3 runs are also checked as the other cases are (statics, symmetry, preload).
TEST(VoussoirPaper, Table3DeflectionRatios) {
  std::map<std::string, RunResult> r;
  for (const char* id : {"T3-full", "T2-2", "T3-half", "T3-half-old"}) {
    SCOPED_TRACE(id);
    r[id] = run_case(id);
    if (std::string(id) != "T2-2") expect_statics_symmetry_and_preload(id, r[id]);
    ASSERT_FALSE(::testing::Test::HasFatalFailure());
  }
  const double full = voussoir_levels(r["T3-full"]).back().midspan_deflection /
                      voussoir_levels(r["T2-2"]).back().midspan_deflection;
  const double half = voussoir_levels(r["T3-half"]).back().midspan_deflection /
                      voussoir_levels(r["T3-half-old"]).back().midspan_deflection;
  EXPECT_NEAR(full, boon2015_ratio_full(), 0.05 * boon2015_ratio_full());
  EXPECT_NEAR(half, boon2015_ratio_half(), 0.05 * boon2015_ratio_half());
}

}  // namespace
}  // namespace blockdem
