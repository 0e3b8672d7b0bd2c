// End-to-end tests of `blockdem calibrate normal|shear|cy`: the report and CSVs written, the
// joint-law block parsing as a scenario's joint-law table, the plots (and their absence stated
// when matplotlib is missing), and bad input rejected with a named row or parameter, a non-zero
// exit code and nothing written.
#include <gtest/gtest.h>

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "blockdem/contact/normal_laws.hpp"
#include "blockdem/contact/shear_laws.hpp"
#include "calibration_test_support.hpp"
#include "support/cli_runner.hpp"

// A namespace of this file's own: the unity build (cmake/build_speed.cmake) compiles it together
// with other test files that define helpers of the same names.
namespace blockdem::cmd_calibrate_test {
namespace {

namespace fs = std::filesystem;
using test::relative_error;

using test::CommandOutput;
using test::run_cli;

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The line of stdout that starts with `prefix`, without the prefix.
std::string line_after(const std::string& text, const std::string& prefix) {
  const auto at = text.find(prefix);
  if (at == std::string::npos) return "";
  const auto start = at + prefix.size();
  return text.substr(start, text.find('\n', start) - start);
}

// Parses a printed TOML line ("normal = { ... }") as a scenario would, returns the law name and
// its numeric parameters; every number must be a TOML float, as scenario tables expect.
std::pair<std::string, std::map<std::string, double>> parse_toml_law(const std::string& line,
                                                                     const std::string& key) {
  const toml::table doc = toml::parse(line);
  const toml::table* law = doc[key].as_table();
  EXPECT_NE(law, nullptr) << line;
  std::pair<std::string, std::map<std::string, double>> out;
  if (law == nullptr) return out;
  for (const auto& [name, node] : *law) {
    if (name.str() == "law") {
      out.first = node.value<std::string>().value_or("");
    } else {
      EXPECT_TRUE(node.is_floating_point()) << name.str() << " in " << line;
      out.second[std::string(name.str())] = node.value<double>().value_or(0.0);
    }
  }
  return out;
}

TEST(CliCalibrate, NormalWritesReportCsvsAndAPastableExponentialLaw) {
  const fs::path data = test::synthetic_data("normal", "cli_normal.csv");
  const fs::path out = test::scratch_directory() / "cli_normal_out";
  const CommandOutput run = run_cli(
      "calibrate normal --data '" + data.string() +
      "' --modulus 5.6e9 --height 0.138 --joints 3 --no-figures --out '" + out.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = read_json(out / "calibration.json");
  EXPECT_EQ(report["command"], "calibrate normal");
  EXPECT_TRUE(report["data"]["synthetic"].get<bool>());
  EXPECT_LT(relative_error(report["exponential"]["a_Pa"].get<double>(), 0.5405e5), 1e-6);
  EXPECT_LT(relative_error(report["exponential"]["b_per_m"].get<double>(), 3.7e4), 1e-6);
  EXPECT_DOUBLE_EQ(
      report["exponential"]["k0_Pa_per_m"].get<double>(),
      report["exponential"]["a_Pa"].get<double>() * report["exponential"]["b_per_m"].get<double>());
  EXPECT_EQ(report["exponential"]["fit"]["residuals_m"].size(), 25u);
  EXPECT_EQ(report["plots"], "not requested (--no-figures)");
  for (const auto& f : report["files"]) EXPECT_TRUE(fs::exists(out / f.get<std::string>()));

  // The TOML line on stdout builds the law a scenario would build, to the 7 digits printed.
  const std::string toml_line = line_after(run.out, "joint law (TOML): ");
  EXPECT_EQ(toml_line, report["joint_law"]["toml"].get<std::string>());
  const auto [name, params] = parse_toml_law(toml_line, "normal");
  const auto law = std::get<ExponentialNormal>(normal_law_from_params(name, params));
  EXPECT_LT(relative_error(law.a, 0.5405e5), 1e-6);
  EXPECT_LT(relative_error(law.b, 3.7e4), 1e-6);
  const nlohmann::json block = nlohmann::json::parse(line_after(run.out, "joint law (JSON): "));
  EXPECT_EQ(block["normal"]["law"], "exponential");
  EXPECT_EQ(block["normal"]["a"].get<double>(), law.a);
}

TEST(CliCalibrate, ShearAndCyPrintShearLawsAScenarioAccepts) {
  const fs::path degrading = test::synthetic_data("shear --model degrading", "cli_degrading.csv");
  const CommandOutput shear = run_cli("calibrate shear --data '" + degrading.string() + "'");
  ASSERT_EQ(shear.exit_code, 0) << shear.err;
  const auto [shear_name, shear_params] =
      parse_toml_law(line_after(shear.out, "joint law (TOML): "), "shear");
  EXPECT_EQ(shear_name, "degrading");
  const auto d = std::get<DegradingShear>(shear_law_from_params(shear_name, shear_params));
  EXPECT_LT(relative_error(d.power_laws.stiffness_coefficient, 1.9e6), 1e-6);
  EXPECT_LT(relative_error(d.power_laws.peak_exponent, 0.213), 1e-6);
  EXPECT_NE(shear.out.find("next: blockdem calibrate cy --data"), std::string::npos);

  const fs::path cy_data = test::synthetic_data("shear --model cy", "cli_cy.csv");
  const CommandOutput cy = run_cli("calibrate cy --data '" + cy_data.string() +
                                   "' --stiffness-coefficient 1.9e6 --stiffness-exponent 0.7");
  ASSERT_EQ(cy.exit_code, 0) << cy.err;
  const auto [cy_name, cy_params] =
      parse_toml_law(line_after(cy.out, "joint law (TOML): "), "shear");
  EXPECT_EQ(cy_name, "continuously_yielding");
  const auto c = std::get<ContinuouslyYieldingShear>(shear_law_from_params(cy_name, cy_params));
  EXPECT_LT(relative_error(c.strength.friction_deg(), 40.0), 1e-6);
  EXPECT_LT(relative_error(c.power_laws.peak_coefficient, 2e-6), 1e-6);
  EXPECT_EQ(c.power_laws.stiffness_exponent, 0.7);
}

TEST(CliCalibrate, WritesPngPlotsOrSaysWhyNot) {
  const fs::path data = test::synthetic_data("normal --noise 0.02", "cli_plots.csv");
  const std::string args = "calibrate normal --data '" + data.string() +
                           "' --modulus 5.6e9 --height 0.138 --joints 3 --out '";
  // With Debian's python3-matplotlib (default interpreter): the PNG is written and listed.
  const fs::path with = test::scratch_directory() / "cli_plots_out";
  const CommandOutput plotted = run_cli(args + with.string() + "'");
  ASSERT_EQ(plotted.exit_code, 0) << plotted.err;
  const nlohmann::json report = read_json(with / "calibration.json");
  EXPECT_EQ(report["plots"], "written") << report["plots"];
  ASSERT_EQ(report["figures"].size(), 1u);
  EXPECT_GT(fs::file_size(with / report["figures"][0].get<std::string>()), 10000u);

  // Without an interpreter: exit 0, a warning, and JSON and CSVs written all the same.
  const fs::path without = test::scratch_directory() / "cli_no_plots_out";
  const CommandOutput missing =
      run_cli(args + without.string() + "' --python /nonexistent/python3");
  ASSERT_EQ(missing.exit_code, 0) << missing.err;
  EXPECT_NE(missing.err.find("warning: no PNG plots written"), std::string::npos) << missing.err;
  const nlohmann::json bare = read_json(without / "calibration.json");
  EXPECT_EQ(bare["plots"].get<std::string>().rfind("not written: ", 0), 0u) << bare["plots"];
  EXPECT_TRUE(bare["figures"].empty());
  EXPECT_TRUE(fs::exists(without / "normal_fit_points.csv"));
  EXPECT_FALSE(fs::exists(without / "normal_fit.png"));
}

struct BadInput {
  const char* name;
  const char* command;   ///< "normal", "shear" or "cy"
  const char* options;   ///< extra options
  const char* csv;       ///< file contents; {} for the synthetic normal data set
  const char* expected;  ///< a substring of the error message
};

const char* const kNormalHeader = "stress_Pa,displacement_m\n";

class CliCalibrateBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliCalibrateBadInput, FailsNamingTheProblemAndWritesNothing) {
  const BadInput& c = GetParam();
  const fs::path data = c.csv == nullptr
                            ? test::synthetic_data("normal", "bad_base.csv")
                            : test::write_file(std::string("bad_") + c.name + ".csv", c.csv);
  const fs::path out = test::scratch_directory() / (std::string("bad_out_") + c.name);
  const CommandOutput run = run_cli(std::string("calibrate ") + c.command + " --data '" +
                                    data.string() + "' --out '" + out.string() + "' " + c.options);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out)) << "an output directory was created";
  EXPECT_EQ(run.out.find("joint law"), std::string::npos) << run.out;
}

const char* const kColumn = "--modulus 5.6e9 --height 0.138 --joints 3";

INSTANTIATE_TEST_SUITE_P(
    Rejections, CliCalibrateBadInput,
    ::testing::Values(
        BadInput{"too_few_points", "normal", kColumn,
                 "stress_Pa,displacement_m\n0,0\n1e5,5e-5\n2e5,8e-5\n",
                 "bad_too_few_points.csv: 3 data rows"},
        BadInput{"non_monotonic", "normal", kColumn,
                 "stress_Pa,displacement_m\n0,0\n2e5,5e-5\n1e5,4e-5\n3e5,9e-5\n4e5,1e-4\n",
                 "bad_non_monotonic.csv:4: stress_Pa = 1e+05 is not greater"},
        BadInput{"negative_stress", "normal", kColumn,
                 "stress_Pa,displacement_m\n-1e5,0\n0,0\n1e5,5e-5\n2e5,8e-5\n3e5,9e-5\n",
                 "bad_negative_stress.csv:2: stress_Pa = -1e+05 is negative"},
        BadInput{"nan", "normal", kColumn,
                 "# lab\nstress_Pa,displacement_m\n0,0\n1e5,NaN\n2e5,8e-5\n3e5,9e-5\n4e5,1e-4\n",
                 "bad_nan.csv:4: column 'displacement_m' is nan"},
        BadInput{"missing_column", "normal", kColumn, "stress_Pa\n0\n1e5\n",
                 "bad_missing_column.csv:1: missing column 'displacement_m'"},
        BadInput{"soft_modulus", "normal", "--modulus 1e8 --height 0.138 --joints 3", nullptr,
                 "bad_base.csv:8: joint closure (d - sigma H / E) / N = "},
        BadInput{"tall_column", "normal", "--modulus 5.6e9 --height 7 --joints 3", nullptr,
                 "check the modulus (E = 5.6e+09 Pa) and the height (H = 7 m)"},
        BadInput{"no_joints", "normal", "--modulus 5.6e9 --height 0.138 --joints 0", nullptr,
                 "joints (number of equivalent joints) must be at least 1, got 0"},
        BadInput{"shear_backwards", "shear", "",
                 "normal_stress_Pa,shear_displacement_m,shear_stress_Pa\n1e4,0,0\n1e4,2e-6,3e3\n"
                 "1e4,1e-6,4e3\n",
                 "bad_shear_backwards.csv:4: shear_displacement_m = 1e-06 is not greater"},
        BadInput{"shear_wrong_file", "shear", "", nullptr,
                 "bad_base.csv:6: unexpected column 'stress_Pa'"},
        BadInput{"cy_stiffness", "cy", "--stiffness-coefficient 1.9e6 --stiffness-exponent -1",
                 nullptr, "stiffness_exponent (B of eq 7"}),
    [](const ::testing::TestParamInfo<BadInput>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace blockdem::cmd_calibrate_test
