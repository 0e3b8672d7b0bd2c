// End-to-end tests of `blockdem lab`: bad input (physically impossible law parameters, bad path
// parameters) gives a non-zero exit and a message naming the law and the parameter on stderr;
// good input gives the kernel's numbers as JSON on stdout and the CSV files.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>
#include "support/cli_runner.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

using test::CommandOutput;
using test::run_cli;

struct BadInput {
  const char* name;
  const char* arguments;
  std::vector<const char*> expected;  // substrings of the error message
};

class CliLabBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliLabBadInput, ExitsNonZeroNamingTheLawAndTheParameter) {
  const CommandOutput run = run_cli(GetParam().arguments);
  EXPECT_NE(run.exit_code, 0) << run.out;
  EXPECT_TRUE(run.out.empty()) << run.out;
  for (const char* text : GetParam().expected) {
    EXPECT_NE(run.err.find(text), std::string::npos) << "missing '" << text << "' in: " << run.err;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Laws, CliLabBadInput,
    ::testing::Values(
        BadInput{"negative_normal_stiffness",
                 "lab compression --max-stress 1e6 --normal law=linear,stiffness=-1e10",
                 {"normal law 'linear'", "'stiffness'"}},
        BadInput{"negative_shear_stiffness",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=linear,stiffness=-1e9",
                 {"shear law 'linear'", "'stiffness'"}},
        BadInput{"negative_stress_linear_k0",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=stress_linear,k0=-1e8",
                 {"shear law 'stress_linear'", "'k0'"}},
        BadInput{"friction_zero",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=continuously_yielding,friction_deg=0",
                 {"shear law 'continuously_yielding'", "'friction_deg'"}},
        BadInput{"friction_ninety",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=linear,friction_deg=90",
                 {"shear law 'linear'", "'friction_deg'"}},
        BadInput{"friction_negative",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=degrading,friction_deg=-10",
                 {"shear law 'degrading'", "'friction_deg'"}},
        BadInput{"u_peak_zero",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=continuously_yielding,peak_coefficient=0",
                 {"shear law 'continuously_yielding'", "'peak_coefficient'"}},
        BadInput{"u_peak_negative",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=degrading,peak_coefficient=-2e-6",
                 {"shear law 'degrading'", "'peak_coefficient'"}},
        BadInput{"nan_normal_parameter",
                 "lab compression --max-stress 1e6 --normal law=exponential,a=nan,b=3.7e4",
                 {"normal law 'exponential'", "'a'"}},
        BadInput{"nan_shear_parameter",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=continuously_yielding,stiffness_coefficient=nan",
                 {"shear law 'continuously_yielding'", "'stiffness_coefficient'"}},
        BadInput{"unknown_law",
                 "lab compression --max-stress 1e6 --normal law=hyperbolic",
                 {"unknown normal law 'hyperbolic'"}},
        BadInput{"unknown_parameter",
                 "lab shear --normal-stress 2e4 --max-shear-displacement 1e-4 "
                 "--shear law=linear,stifness=1e9",
                 {"shear law 'linear'", "unknown parameter 'stifness'"}},
        BadInput{"not_a_number",
                 "lab compression --max-stress 1e6 --normal law=linear,stiffness=ten",
                 {"normal law", "'stiffness' = 'ten' is not a number"}},
        BadInput{"negative_normal_stress",
                 "lab shear --normal-stress -2e4 --max-shear-displacement 1e-4",
                 {"shear test", "normal_stress"}},
        BadInput{"nan_max_stress",
                 "lab compression --max-stress nan",
                 {"compression test", "max_stress"}},
        BadInput{"no_path_maximum", "lab compression", {"--max-closure", "--max-stress"}}),
    [](const auto& case_info) { return std::string(case_info.param.name); });

TEST(CliLab, CompressionPrintsTheKernelCurveAndTheDemComparison) {
  const std::filesystem::path out = test::temp_path("lab_cli");
  const CommandOutput run = run_cli(
      "lab compression --normal law=linear,stiffness=1e10 --max-stress 1e6 --steps 4 "
      "--dem --no-figures --out " +
      out.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  // Linear law: u_max = sigma_max / k_n.
  EXPECT_NEAR(summary["path"]["max_closure_m"].get<double>(), 1e-4, 1e-16);
  EXPECT_EQ(summary["path"]["points"].get<int>(), 9);
  EXPECT_EQ(summary["dem"]["levels"].get<int>(), 7);
  EXPECT_TRUE(summary["dem"]["converged"].get<bool>());
  EXPECT_LT(summary["dem"]["max_relative_closure_difference"].get<double>(), 0.01);
  std::ifstream csv(out / "compression.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("cycle,branch,closure_m,normal_stress_Pa,tangent_stiffness_Pa_per_m,"
                         "dem_closure_m",
                         0),
            0u)
      << header;
}

TEST(CliLab, ShearReachesTanPhiOfTheGivenFrictionAngle) {
  const CommandOutput run = run_cli(
      "lab shear --shear law=linear,stiffness=1e9,friction_deg=30 --normal-stress 1e5 "
      "--max-shear-displacement 1e-3 --steps 100");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_NEAR(summary["kernel"]["final_mobilised_friction"].get<double>(), std::sqrt(3.0) / 3.0,
              1e-12);
  EXPECT_EQ(summary["shear_law"]["law"], "linear");
}

}  // namespace
}  // namespace blockdem
