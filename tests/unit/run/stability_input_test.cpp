// Bad input to the stability searches: every error names the file, the key and the reason,
// `blockdem run` exits 2; an error found before the run starts leaves no output folder, one
// found while running keeps what the run wrote before it.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

namespace stability_input_cli {

std::string read_text(const std::filesystem::path& f) {
  std::ifstream in(f);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// `blockdem run FILE --out OUT --quiet --no-figures MORE` (without --quiet when `quiet` is
/// false), stderr to `err`; the exit code.
int run_cli(const std::filesystem::path& file, const std::filesystem::path& out,
            const std::string& more, const std::filesystem::path& err, bool quiet = true) {
  const std::string cmd = std::string(BLOCKDEM_CLI_PATH) + " run " + file.string() + " --out " +
                          out.string() + (quiet ? " --quiet" : "") + " --no-figures " + more +
                          " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status));
  return WEXITSTATUS(status);
}

nlohmann::json summary_of(const std::filesystem::path& out) {
  return nlohmann::json::parse(read_text(out / "summary.json"));
}

}  // namespace stability_input_cli

// Bounds that do not bracket the failure (F = tan 40 / tan 30 = 1.45): both stable, and both
// failed. The error is found only after two trials: the CLI exits 2 with a message naming the
// file, the key, the factors tried and what each did, and keeps what the run wrote before it
// (the settling and tilting stages' outputs), with summary.json saying where and why it stopped
// and the state before the stage saved for a corrected restart.
TEST(StabilityInput, BoundsNotBracketingSayWhichFactorsWereTried) {
  using namespace stability_input_cli;
  for (const std::string bounds : {"[1.1, 1.3]", "[1.6, 2.0]"}) {
    const std::string text = test::incline_scenario(
        30, 40, 0.1, 0.02, sr_stage("factor_bounds = " + bounds + "\nmax_steps = 6000\n"));
    const auto dir = test::temp_path("stab_input");
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto file = dir / "srm.toml";
    std::ofstream(file) << text;
    const auto out = dir / "out";
    EXPECT_EQ(run_cli(file, out, "", dir / "err.txt"), 2);
    const std::string msg = read_text(dir / "err.txt");
    EXPECT_NE(msg.find("srm.toml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("stages[3].factor_bounds"), std::string::npos) << msg;
    EXPECT_NE(msg.find(bounds == "[1.1, 1.3]" ? "both stable" : "both failed"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find(bounds == "[1.1, 1.3]" ? "F = 1.1" : "F = 1.6"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--restart " + (out / "checkpoint.bdck").string()), std::string::npos)
        << msg;
    // What the first two stages wrote stays.
    for (const char* kept : {"summary.json", "history.csv", "blocks.csv", "checkpoint.bdck"})
      EXPECT_TRUE(std::filesystem::exists(out / kept)) << kept;
    const auto summary = summary_of(out);
    EXPECT_EQ(summary["status"], "input_error");
    ASSERT_EQ(summary["stages"].size(), 3u);
    EXPECT_EQ(summary["stages"][0]["status"], "completed");
    EXPECT_EQ(summary["stages"][2]["name"], "srm");
    EXPECT_EQ(summary["stages"][2]["status"], "input_error");
    EXPECT_NE(summary["stages"][2]["message"].get<std::string>().find("factor_bounds"),
              std::string::npos);
  }
}

// Branching: the run above, stopped by its bounds, continues from the state it saved with
// corrected bounds (a scenario that differs only in its last stage) and finds the same factor
// of safety, to the last bit, as a fresh run with those bounds. A scenario that differs before the
// checkpoint's stage (another friction angle) is refused with exit 2, its folder untouched. A
// restart from the same checkpoint with the bad bounds meets the same error again (the state
// continues the run bit for bit).
TEST(StabilityInput, ABoundsErrorContinuesWithCorrectedBoundsFromItsCheckpoint) {
  using namespace stability_input_cli;
  const auto dir = test::temp_path("stab_branch");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  const std::string good_stage =
      sr_stage("factor_bounds = [1.0, 3.0]\ntolerance = 0.05\nmax_steps = 6000\n");
  const auto bad = write("bad.toml", test::incline_scenario(30, 40, 0.1, 0.02,
                                                            sr_stage("factor_bounds = [1.1, 1.3]"
                                                                     "\nmax_steps = 6000\n")));
  // The corrected file, written anew (comments and spacing do not count).
  const auto good = write(
      "good.toml", "# corrected bounds\n" + test::incline_scenario(30, 40, 0.1, 0.02, good_stage));
  const auto other = write("other.toml", test::incline_scenario(30, 38, 0.1, 0.02, good_stage));
  const auto out = dir / "out";
  EXPECT_EQ(run_cli(bad, out, "--checkpoint-every 1500", dir / "e1.txt"), 2);
  const auto checkpoint = out / "checkpoint.bdck";
  ASSERT_TRUE(std::filesystem::exists(checkpoint));

  EXPECT_EQ(run_cli(good, dir / "fresh", "", dir / "e2.txt"), 0) << read_text(dir / "e2.txt");
  EXPECT_EQ(
      run_cli(good, dir / "branch", "--restart " + checkpoint.string(), dir / "e3.txt", false), 0)
      << read_text(dir / "e3.txt");
  const auto fresh = summary_of(dir / "fresh");
  const auto branch = summary_of(dir / "branch");
  ASSERT_TRUE(fresh.contains("factor_of_safety")) << fresh.dump();
  EXPECT_EQ(branch["status"], "completed");
  EXPECT_EQ(branch["factor_of_safety"], fresh["factor_of_safety"]);
  EXPECT_EQ(read_text(dir / "branch" / "strength_reduction.csv"),
            read_text(dir / "fresh" / "strength_reduction.csv"));
  EXPECT_EQ(read_text(dir / "branch" / "history.csv"), read_text(dir / "fresh" / "history.csv"));
  EXPECT_EQ(branch["scenario"], good.string());

  // The restart says what it compared (shown without --quiet).
  const std::string said = read_text(dir / "e3.txt");
  EXPECT_NE(said.find("stages 1 to 2 are the same"), std::string::npos) << said;

  // Another friction angle: refused before anything is written.
  EXPECT_EQ(run_cli(other, dir / "refused", "--restart " + checkpoint.string(), dir / "e5.txt"), 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "refused"));
  EXPECT_NE(read_text(dir / "e5.txt").find("written for another scenario"), std::string::npos)
      << read_text(dir / "e5.txt");

  // The bad bounds again, from the same state: the same error.
  EXPECT_EQ(run_cli(bad, dir / "again", "--restart " + checkpoint.string(), dir / "e6.txt"), 2);
  const std::string again = read_text(dir / "e6.txt");
  EXPECT_NE(again.find("both stable"), std::string::npos) << again;
  EXPECT_NE(again.find("F = 1.1"), std::string::npos) << again;
}

}  // namespace
}  // namespace blockdem
