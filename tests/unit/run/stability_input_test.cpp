// Bad input to the stability searches: every error names the file, the key and the reason,
// `blockdem run` exits 2 and leaves no output folder (but the restart checkpoints it wrote).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../../validation/stability_support.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

std::string sr_stage(const std::string& keys) {
  return "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\n" + keys;
}

ScenarioError error_of(const std::string& text) {
  try {
    const Scenario sc = parse_scenario(text, "case.toml");
    build_world(sc);
  } catch (const ScenarioError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return ScenarioError("", "", "");
}

TEST(StabilityInput, ToleranceMustBePositive) {
  const ScenarioError e =
      error_of(test::incline_scenario(30, 40, 0.1, 0.02, sr_stage("tolerance = 0.0\n")));
  EXPECT_EQ(e.key(), "stages[3].tolerance");
  EXPECT_NE(e.reason().find("> 0"), std::string::npos) << e.what();
}

TEST(StabilityInput, UnknownLawName) {
  const ScenarioError e =
      error_of(test::incline_scenario(30, 40, 0.1, 0.02, sr_stage("laws = [\"bedding\"]\n")));
  EXPECT_EQ(e.key(), "stages[3].laws");
  EXPECT_NE(e.reason().find("bedding"), std::string::npos) << e.what();
  EXPECT_NE(e.reason().find("joint"), std::string::npos) << "lists the known laws";
}

TEST(StabilityInput, BoundsMustBeTwoIncreasingFactors) {
  EXPECT_EQ(
      error_of(test::incline_scenario(30, 40, 0.1, 0.02, sr_stage("factor_bounds = [2.0, 1.0]\n")))
          .key(),
      "stages[3].factor_bounds");
  EXPECT_EQ(error_of(test::incline_scenario(30, 40, 0.1, 0.02, sr_stage("factor_bounds = [1.0]\n")))
                .key(),
            "stages[3].factor_bounds");
}

TEST(StabilityInput, StrengthKeysOnlyOnAStrengthReductionStage) {
  const std::string text = test::incline_scenario(
      30, 40, 0.1, 0.02, "[[stages]]\nname = \"x\"\nfactor_bounds = [1.0, 2.0]\n");
  EXPECT_EQ(error_of(text).key(), "stages[3].factor_bounds");
}

TEST(StabilityInput, FindCollapseNeedsGravity) {
  const std::string text =
      test::incline_scenario(30, 40, 0.1, 0.02, "[[stages]]\nname = \"x\"\nfind_collapse = true\n");
  EXPECT_EQ(error_of(text).key(), "stages[3].find_collapse");
}

// Bounds that do not bracket the failure (F = tan 40 / tan 30 = 1.45): both stable, and both
// failed. The error names the factors tried and what each did; the CLI exits 2 and writes
// nothing.
TEST(StabilityInput, BoundsNotBracketingSayWhichFactorsWereTried) {
  for (const std::string bounds : {"[1.1, 1.3]", "[1.6, 2.0]"}) {
    const std::string text = test::incline_scenario(
        30, 40, 0.1, 0.02, sr_stage("factor_bounds = " + bounds + "\nmax_steps = 60000\n"));
    const auto dir = test::temp_path("stab_input");
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto file = dir / "srm.toml";
    std::ofstream(file) << text;
    const auto out = dir / "out";
    const auto err = dir / "err.txt";
    const std::string cmd = std::string(BLOCKDEM_CLI_PATH) + " run " + file.string() + " --out " +
                            out.string() + " --quiet 2>" + err.string();
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing may be written";
    std::ifstream in(err);
    const std::string msg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(msg.find("srm.toml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("factor_bounds"), std::string::npos) << msg;
    EXPECT_NE(msg.find(bounds == "[1.1, 1.3]" ? "both stable" : "both failed"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find(bounds == "[1.1, 1.3]" ? "F = 1.1" : "F = 1.6"), std::string::npos) << msg;
  }
}

// The same error found after the run has written restart checkpoints (at the ends of its
// first two stages): the results are removed as before, the last checkpoint is kept and named
// (the run's progress, not a result), and a restart from it meets the same error again (the
// checkpoint is whole and continues the run bit for bit, up to the same failure).
TEST(StabilityInput, AnErrorWhileRunningKeepsTheRunsCheckpoints) {
  const std::string text = test::incline_scenario(
      30, 40, 0.1, 0.02, sr_stage("factor_bounds = [1.1, 1.3]\nmax_steps = 60000\n"));
  const auto dir = test::temp_path("stab_keep");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "srm.toml";
  std::ofstream(file) << text;
  const auto run = [&](const std::filesystem::path& out, const std::string& more,
                       const std::filesystem::path& err) {
    const std::string cmd = std::string(BLOCKDEM_CLI_PATH) + " run " + file.string() + " --out " +
                            out.string() + " --quiet " + more + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    EXPECT_TRUE(WIFEXITED(status));
    return WEXITSTATUS(status);
  };
  const auto read = [](const std::filesystem::path& f) {
    std::ifstream in(f);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const auto out = dir / "out";
  EXPECT_EQ(run(out, "--checkpoint-every 1000000", dir / "err.txt"), 2);
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(out))
    left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"checkpoint.bdck", "checkpoint.bdck.prev"}));
  const std::string msg = read(dir / "err.txt");
  EXPECT_NE(msg.find("both stable"), std::string::npos) << msg;
  EXPECT_NE(msg.find("checkpoint is kept: " + (out / "checkpoint.bdck").string()),
            std::string::npos)
      << msg;
  const auto again = dir / "again";
  EXPECT_EQ(run(again, "--restart " + (out / "checkpoint.bdck").string(), dir / "err2.txt"), 2);
  const std::string msg2 = read(dir / "err2.txt");
  EXPECT_NE(msg2.find("both stable"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("F = 1.1"), std::string::npos) << msg2;
}

}  // namespace
}  // namespace blockdem
