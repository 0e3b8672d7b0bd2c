// End-to-end test of `blockdem analytic voussoir`: the JSON on stdout equals the library's
// solution for the same inputs, and invalid input gives a non-zero exit and a message on stderr.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>

#include "blockdem/analysis/voussoir_analytic.hpp"
#include "support/cli_runner.hpp"

namespace blockdem {
namespace {

using test::CommandOutput;
using test::run_cli;

TEST(CliAnalyticVoussoir, PrintsTheLibrarySolutionAsJson) {
  // The paper's full-block beam at 40 g: S = 276 mm, T = 46 mm, 1207 kg/m^3, E_rm = k_n s with
  // k_n = 10 GPa/m and s = 46 mm, width 46 mm.
  const CommandOutput run = run_cli(
      "analytic voussoir --span 0.276 --depth 0.046 --density 1207 --gravity 392.4 "
      "--modulus 4.6e8 --width 0.046 --compressive-strength 20e6 --friction-deg 40");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);

  VoussoirBeamDef beam;
  beam.span = 0.276;
  beam.depth = 0.046;
  beam.unit_weight = 1207.0 * 392.4;
  beam.rock_mass_modulus = 4.6e8;
  beam.width = 0.046;
  beam.compressive_strength = 20e6;
  beam.friction_angle = 40.0 * std::numbers::pi / 180.0;
  const VoussoirResult expected = solve_voussoir_beam(beam);
  ASSERT_EQ(expected.status, VoussoirStatus::stable);
  EXPECT_EQ(report["status"], "stable");
  EXPECT_DOUBLE_EQ(report["n"].get<double>(), expected.equilibrium->n);
  EXPECT_DOUBLE_EQ(report["lever_arm_m"].get<double>(), expected.equilibrium->lever_arm);
  EXPECT_DOUBLE_EQ(report["midspan_deflection_m"].get<double>(),
                   expected.equilibrium->midspan_deflection);
  EXPECT_DOUBLE_EQ(report["max_stress_Pa"].get<double>(), expected.equilibrium->max_stress);
  EXPECT_DOUBLE_EQ(report["thrust_N_per_m"].get<double>(), expected.equilibrium->thrust_per_width);
  EXPECT_DOUBLE_EQ(report["thrust_N"].get<double>(), *expected.equilibrium->thrust);
  EXPECT_DOUBLE_EQ(report["sliding_safety_factor"].get<double>(),
                   *expected.equilibrium->sliding_safety_factor);
  // Inputs echoed in the command line's units.
  EXPECT_DOUBLE_EQ(report["inputs"]["density_kg_m3"].get<double>(), 1207.0);
  EXPECT_DOUBLE_EQ(report["inputs"]["gravity_m_s2"].get<double>(), 392.4);
  EXPECT_DOUBLE_EQ(report["inputs"]["friction_deg"].get<double>(), 40.0);
}

TEST(CliAnalyticVoussoir, ReportsSnapThroughAsAResult) {
  const CommandOutput run = run_cli(
      "analytic voussoir --span 10 --depth 0.2 --density 2600 --gravity 9.81 --modulus 1e6");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["status"], "snap_through");
  EXPECT_TRUE(report["n"].is_null());
  EXPECT_LT(report["buckling"]["modulus_safety_factor"].get<double>(), 1.0);
}

TEST(CliAnalyticVoussoir, RejectsInvalidInputOnStderr) {
  const CommandOutput negative_span = run_cli(
      "analytic voussoir --span -1 --depth 0.046 --density 1207 --gravity 9.81 --modulus 4.6e8");
  EXPECT_NE(negative_span.exit_code, 0);
  EXPECT_TRUE(negative_span.out.empty());
  EXPECT_NE(negative_span.err.find("span"), std::string::npos) << negative_span.err;

  const CommandOutput zero_density = run_cli(
      "analytic voussoir --span 1 --depth 0.046 --density 0 --gravity 9.81 --modulus 4.6e8");
  EXPECT_NE(zero_density.exit_code, 0);
  EXPECT_NE(zero_density.err.find("--density"), std::string::npos) << zero_density.err;

  const CommandOutput missing = run_cli("analytic voussoir --span 1");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("required"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace blockdem
