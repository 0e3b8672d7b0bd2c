// Every `blockdem run` writes report.md beside summary.json, with the figures it could draw: each
// shipped example (cut short with --max-steps) has a report that names every stage, links only
// figures that exist and are not empty, and is listed in summary.json's record; a figure that
// fails is one warning line and a line in the report, never a Python traceback.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/sanitized_run.hpp"
#include "support/temp_path.hpp"

namespace blockdem::run_report_test {
namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> examples() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/examples"))
    if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// The report of `out` against its summary.json: the title, every stage's name, the factor of
/// safety as summary.json has it, each linked figure present and drawn, the report in the record.
void expect_report_matches_summary(const fs::path& out, const std::string& err) {
  ASSERT_TRUE(fs::exists(out / "report.md")) << err;
  const std::string report = read(out / "report.md");
  const nlohmann::json summary = nlohmann::json::parse(read(out / "summary.json"));
  EXPECT_EQ(report.rfind("# " + summary["title"].get<std::string>() + "\n", 0), 0u) << report;
  for (const auto& stage : summary["stages"])
    EXPECT_NE(report.find("| " + stage["name"].get<std::string>() + " |"), std::string::npos)
        << stage["name"] << "\n"
        << report;
  if (summary.contains("factor_of_safety")) {
    char f[32];
    std::snprintf(f, sizeof f, "**F = %.4g**", summary["factor_of_safety"]["value"].get<double>());
    EXPECT_NE(report.find(f), std::string::npos) << report;
  }
  const std::regex link(R"(\]\(([A-Za-z0-9_.]+\.png)\))");
  int figures = 0;
  for (auto it = std::sregex_iterator(report.begin(), report.end(), link);
       it != std::sregex_iterator(); ++it, ++figures) {
    const fs::path png = out / (*it)[1].str();
    ASSERT_TRUE(fs::exists(png)) << png;
    EXPECT_GT(fs::file_size(png), 5000u) << png;
    EXPECT_EQ(read(png).substr(1, 3), "PNG") << png;
  }
  std::set<std::string> recorded;
  for (const auto& f : summary["files"]) recorded.insert(f["path"].get<std::string>());
  EXPECT_TRUE(recorded.count("report.md")) << "report.md not in summary.json's files";
  EXPECT_EQ(err.find("Traceback"), std::string::npos) << err;
}

class ExampleReport : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleReport, NamesEveryStageAndShowsItsFigures) {
  const std::string name = GetParam();
  // Under the sanitizers the program is 10-100 times slower: two examples cover the code there.
  if (test::sanitized_run() && name != "column" && name != "planar_sliding")
    GTEST_SKIP() << "one of the examples the ordinary run covers";
  const fs::path out = test::temp_path("run_report_" + name);
  fs::remove_all(out);
  const fs::path file = fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/examples" / (name + ".toml");
  const test::CommandOutput r = test::run_cli("run '" + file.string() + "' --out '" + out.string() +
                                              "' --max-steps 200 --quiet");
  // Cut short, a stage is not converged (exit 3), and a strength reduction's bounds may not
  // bracket its failure in 200 steps a trial (an input error, exit 2): both keep the outputs.
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2 || r.exit_code == 3) << r.err;
  expect_report_matches_summary(out, r.err);
  EXPECT_EQ(r.err.find("warning: no"), std::string::npos) << r.err;
  const std::string report = read(out / "report.md");
  // Every run but a beam's shows its blocks and its time histories (200 steps give 3 rows).
  EXPECT_NE(report.find("](blocks_final.png)"), std::string::npos) << report;
  EXPECT_NE(report.find("](time_history.png)"), std::string::npos) << report;
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(ShippedExamples, ExampleReport, ::testing::ValuesIn(examples()),
                         [](const auto& p) { return p.param; });

TEST(RunReport, AFailingFigureIsOneWarningLineAndALineInTheReport) {
  // A tools folder whose time-history script raises and whose other scripts are missing.
  const fs::path dir = test::temp_path("run_report_broken_tools");
  fs::remove_all(dir);
  fs::create_directories(dir / "tools");
  std::ofstream(dir / "tools/plot_time_history.py")
      << "raise RuntimeError('the figure cannot be drawn here')\n";
  const fs::path file = fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/examples/column.toml";
  const fs::path out = dir / "out";
  ASSERT_EQ(setenv("BLOCKDEM_TOOLS_DIR", (dir / "tools").c_str(), 1), 0);
  const test::CommandOutput r =
      test::run_cli("run '" + file.string() + "' --out '" + out.string() + "' --quiet");
  unsetenv("BLOCKDEM_TOOLS_DIR");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("warning: no time history figure: plot_time_history.py failed: "
                       "RuntimeError: the figure cannot be drawn here\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("warning: no model view: the plotting script"), std::string::npos) << r.err;
  expect_report_matches_summary(out, r.err);
  const std::string report = read(out / "report.md");
  EXPECT_NE(report.find("- Not drawn: time history figure: plot_time_history.py failed: "
                        "RuntimeError: the figure cannot be drawn here"),
            std::string::npos)
      << report;
  EXPECT_EQ(report.find(".png)"), std::string::npos) << report;
  fs::remove_all(dir);
}

// --memory-report: one line, the set-up's peak at least the resident size after the set-up
// (a peak is never below the size it ends at), and the run's peak, started again from that
// size, at least that size; without the flag, no line.
TEST(RunReport, MemoryReportGivesTheSetUpsAndTheRunsPeaks) {
  const fs::path file = fs::path(BLOCKDEM_SOURCE_DIR) / "scenarios/examples/column.toml";
  const fs::path out = test::temp_path("run_report_memory");
  fs::remove_all(out);
  const std::string args =
      "run '" + file.string() + "' --out '" + out.string() + "' --quiet --no-figures";
  const test::CommandOutput r = test::run_cli(args + " --memory-report");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::regex line(
      R"(blockdem: process 0 of 1: peak resident memory ([0-9.]+) MiB while setting up )"
      R"(\(reading the scene, building the world; ([0-9.]+) MiB after it\), ([0-9.]+) MiB )"
      R"(while running the stages\n)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, line)) << r.err;
  const double set_up_peak = std::stod(m[1]), after = std::stod(m[2]), run_peak = std::stod(m[3]);
  EXPECT_GT(after, 1.0) << r.err;
  EXPECT_GE(set_up_peak, after) << r.err;
  EXPECT_GE(run_peak, after) << r.err;
  EXPECT_FALSE(std::regex_search(m.suffix().str(), line)) << r.err;
  fs::remove_all(out);
  const test::CommandOutput plain = test::run_cli(args);
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.err.find("resident memory"), std::string::npos) << plain.err;
  fs::remove_all(out);
}

}  // namespace blockdem::run_report_test
