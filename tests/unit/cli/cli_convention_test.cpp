// One convention for every subcommand (README, "Exit codes"): a missing file, an unknown option
// and a bad value are input errors: exit code 2, a message that starts with "blockdem:", and
// nothing written into the output folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/temp_path.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::cli_convention_test {
namespace {

namespace fs = std::filesystem;

struct BadCommand {
  const char* name;
  std::string arguments;  // "OUT" stands for a fresh output folder
};

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = test::temp_path("cli_convention_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string with_out(std::string arguments, const fs::path& out) {
  const auto at = arguments.find("OUT");
  if (at != std::string::npos) arguments.replace(at, 3, "'" + out.string() + "'");
  return arguments;
}

class CliConvention : public ::testing::TestWithParam<BadCommand> {};

TEST_P(CliConvention, InputErrorsExitTwoWithABlockdemMessageAndWriteNothing) {
  const BadCommand& c = GetParam();
  const fs::path out = fresh_folder(c.name);
  const test::CommandOutput r = test::run_cli(with_out(c.arguments, out));
  EXPECT_EQ(r.exit_code, 2) << c.arguments << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("blockdem:", 0), 0u) << "stderr: " << r.err;
  EXPECT_FALSE(fs::exists(out)) << "an input error must write nothing: " << out;
}

const std::string kScenario = std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/examples/column.toml";
const std::string kRockMass = std::string(BLOCKDEM_SOURCE_DIR) + "/scenarios/examples/tunnel.toml";
const std::string kNormalData =
    std::string(BLOCKDEM_SOURCE_DIR) + "/data/synthetic/column_compression_eq4.csv";
const std::string kShearData =
    std::string(BLOCKDEM_SOURCE_DIR) + "/data/synthetic/direct_shear_eq5.csv";

INSTANTIATE_TEST_SUITE_P(
    EverySubcommand, CliConvention,
    ::testing::Values(
        BadCommand{"run_missing_file", "run /no/such/file.toml --out OUT"},
        BadCommand{"run_bad_option", "run '" + kScenario + "' --out OUT --no-such-option"},
        BadCommand{"run_missing_out", "run '" + kScenario + "'"},
        BadCommand{"reproduce_bad_option", "reproduce boon2015 --out OUT --no-such-option"},
        BadCommand{"reproduce_bad_case", "reproduce boon2015 --case T9-9 --out OUT"},
        BadCommand{"reproduce_bad_value", "reproduce boon2015 --mode sideways --out OUT"},
        BadCommand{"reproduce_missing_folder",
                   "reproduce boon2015 --scenarios /no/such/folder --out OUT"},
        BadCommand{"analytic_bad_value",
                   "analytic voussoir --span -1 --depth 0.046 --density 1207 --gravity 9.81 "
                   "--modulus 4.6e8"},
        BadCommand{"analytic_bad_option", "analytic voussoir --no-such-option"},
        BadCommand{
            "lab_bad_value",
            "lab compression --normal 'law=linear,stiffness=-1' --max-closure 1e-4 --out OUT"},
        BadCommand{"lab_bad_option", "lab compression --no-such-option --out OUT"},
        BadCommand{"calibrate_missing_file",
                   "calibrate normal --data /no/such/file.csv --modulus 5.6e9 --height 0.138 "
                   "--joints 3 --out OUT"},
        BadCommand{"calibrate_bad_option", "calibrate normal --no-such-option --out OUT"},
        BadCommand{"no_subcommand_bad_option", "--no-such-option"},
        // Every subcommand: a missing file (where it reads one), an unknown option and a value
        // that is not a number.
        BadCommand{"run_bad_value", "run '" + kScenario + "' --out OUT --threads two"},
        BadCommand{"generate_missing_file", "generate /no/such/file.toml --out OUT"},
        BadCommand{"generate_bad_option",
                   "generate '" + kRockMass + "' --out OUT --no-such-option"},
        BadCommand{"generate_bad_value", "generate '" + kScenario + "' --out OUT"},
        BadCommand{"keyblocks_missing_file", "keyblocks /no/such/file.toml --out OUT"},
        BadCommand{"keyblocks_bad_option",
                   "keyblocks '" + kRockMass + "' --out OUT --no-such-option"},
        BadCommand{"keyblocks_bad_number",
                   "keyblocks '" + kRockMass + "' --out OUT --required-factor high"},
        BadCommand{"keyblocks_bad_value", "keyblocks '" + kScenario + "' --out OUT"},
        BadCommand{"reproduce_bad_number", "reproduce boon2015 --jobs two --out OUT"},
        BadCommand{"analytic_bad_number",
                   "analytic voussoir --span long --depth 0.046 --density 1207 --gravity 9.81 "
                   "--modulus 4.6e8"},
        BadCommand{"lab_shear_bad_option", "lab shear --no-such-option --out OUT"},
        BadCommand{"lab_shear_bad_value",
                   "lab shear --shear 'law=linear,stiffness=1e9,friction_deg=40' "
                   "--normal-stress 1e6 --max-shear-displacement 1e-3 --steps many --out OUT"},
        BadCommand{"lab_figures_bad_option", "lab figures --no-such-option --out OUT"},
        BadCommand{"calibrate_bad_value",
                   "calibrate normal --data '" + kNormalData +
                       "' --modulus stiff --height 0.138 --joints 3 --out OUT"},
        BadCommand{"calibrate_shear_missing_file", "calibrate shear --data /no/such.csv --out OUT"},
        BadCommand{"calibrate_shear_bad_option",
                   "calibrate shear --data '" + kShearData + "' --no-such-option --out OUT"},
        BadCommand{"calibrate_cy_missing_file",
                   "calibrate cy --data /no/such.csv --stiffness-coefficient 1.9e6 "
                   "--stiffness-exponent 0.7 --out OUT"},
        BadCommand{"calibrate_cy_bad_value",
                   "calibrate cy --data '" + kShearData +
                       "' --stiffness-coefficient 1.9e6 --stiffness-exponent half --out OUT"}),
    [](const ::testing::TestParamInfo<BadCommand>& p) { return std::string(p.param.name); });

TEST(CliConvention, HelpAndVersionExitZero) {
  const test::CommandOutput help = test::run_cli("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("reproduce"), std::string::npos);
  const test::CommandOutput version = test::run_cli("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("blockdem ", 0), 0u) << version.out;
}

}  // namespace
}  // namespace blockdem::cli_convention_test
