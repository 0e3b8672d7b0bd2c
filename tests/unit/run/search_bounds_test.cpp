// Stability searches end whatever their numbers: a tolerance below the resolution of the bounds is
// refused at input, a bisection stops where its midpoint equals an end, and a stop asked for
// between two trials or inside one ends the search (status interrupted, a checkpoint before the
// stage that a restart runs again to the same factor of safety).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "../../validation/stability_support.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/run/run_files.hpp"
#include "blockdem/run/stage_driver.hpp"
#include "restart_support.hpp"

extern char** environ;

namespace blockdem::search_bounds_test {

// F = tan 40 / tan 30 = 1.45 for the box on a 30-degree incline: bisected in [0.8, 3.0].
std::string strength_reduction_last(const std::string& tolerance = "0.05") {
  return test::incline_scenario(30, 40, 0.1, 0.02,
                                "[[stages]]\nname = \"srm\"\nkind = \"strength_reduction\"\n"
                                "factor_bounds = [0.8, 3.0]\ntolerance = " +
                                    tolerance + "\n");
}

ScenarioError parse_error(const std::string& text) {
  try {
    parse_scenario(text, "case.toml");
  } catch (const ScenarioError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return ScenarioError("", "", "");
}

TEST(SearchBounds, ToleranceBelowTheResolutionOfTheBoundsIsRefused) {
  const ScenarioError e = parse_error(strength_reduction_last("1e-300"));
  EXPECT_EQ(e.key(), "stages[3].tolerance");
  EXPECT_NE(e.reason().find("at least 3e-12"), std::string::npos) << e.what();
  EXPECT_NE(e.reason().find("got 1e-300"), std::string::npos) << e.what();
  // The tilt stage raised to find a collapse load of about 1 g: 1e-300 g cannot be resolved.
  const ScenarioError c = parse_error(test::incline_scenario(
      30, 40, 0.1, 0.02,
      "[[stages]]\nname = \"up\"\ngravity = [0, 0, -30]\nfind_collapse = true\n"
      "collapse_tolerance = 1e-300\n"));
  EXPECT_EQ(c.key(), "stages[3].collapse_tolerance");
  EXPECT_NE(c.reason().find("got 1e-300"), std::string::npos) << c.what();
}

TEST(SearchBounds, ABisectionEndsWhereItsMidpointEqualsAnEnd) {
  // Asked for a bracket of 1e-300 g (past the input check), the bisection of [1, 2] g halves
  // it until the midpoint is one of its ends: 52 halvings at the resolution of a double (2^-52
  // at 1 to 2), each trial at most 200 steps; before, the same trial repeated for ever.
  const Scenario sc = parse_scenario(test::incline_scenario(0, 40, 0.1, 0.02, ""), "flat.toml");
  World world = build_world(sc);
  ASSERT_TRUE(run_stage(world, sc.stages[0]).converged);
  Stage stage = sc.stages[0];
  stage.max_steps = 200;
  stage.min_steps = 10;
  stage.ramp_steps = 0;
  stage.gravity = Eigen::Vector3d(0.0, 0.0, -2.0 * kOneG);
  int trials = 0;
  const StabilitySearch s =
      find_collapse_load(world, stage, 1.0, 2.0, 1e-300, [&](const StabilityTrial&) { ++trials; });
  EXPECT_FALSE(s.interrupted);
  EXPECT_LE(trials, 60);
  EXPECT_GE(trials, 50);
  const double mid = 0.5 * (s.last_stable + s.first_failed);
  EXPECT_TRUE(mid == s.last_stable || mid == s.first_failed) << "as narrow as doubles go";
}

/// What an observer heard of a stop.
struct Heard final : RunObserver {
  std::vector<std::string> events;
  std::string message;  ///< the interrupted stage's
  void on_interrupted(const World&, const Stage& stage, int level,
                      const StageResult* result) override {
    events.push_back("stopped " + std::to_string(level) + " " + stage.name);
    if (result) message = result->message;
  }
  void on_strength_reduction(const World&, const Stage& stage, int level, const StabilitySearch&,
                             const StageResult&) override {
    events.push_back("factor " + std::to_string(level) + " " + stage.name);
  }
};

TEST(SearchBounds, AStopBetweenTrialsEndsAStrengthReduction) {
  const Scenario sc = parse_scenario(strength_reduction_last(), "srm.toml");
  World world = build_world(sc);
  DriveControl control;
  int asked = 0, trials = 0;
  control.trial_done = [&](const StabilityTrial&) { ++trials; };
  control.between_trials = [&](int level, bool before_stage) {
    EXPECT_EQ(level, 2);
    EXPECT_TRUE(before_stage);
    return ++asked == 3;  // after the bounds and one bisection
  };
  Heard heard;
  const DriveResult d =
      drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), {}, control, {&heard});
  EXPECT_EQ(d.status, RunStatus::interrupted);
  EXPECT_EQ(d.level, 2);
  EXPECT_EQ(trials, 3);
  EXPECT_EQ(heard.events, std::vector<std::string>{"stopped 2 srm"});
}

// Each trial has status lines of its own, however fast it runs: a new line function when the
// trial begins (its rate measured from there), and a line at the trial's first check.
TEST(SearchBounds, EachTrialOfAStrengthReductionHasItsOwnStatusLines) {
  const Scenario sc = parse_scenario(strength_reduction_last(), "srm.toml");
  World world = build_world(sc);
  DriveControl control;
  std::vector<std::vector<std::int64_t>> lines;  // the steps of each line, per line function
  std::vector<std::string> names;
  control.progress = [&](int level) -> ProgressFn {
    if (level != 2) return {};
    lines.emplace_back();
    const std::size_t mine = lines.size() - 1;
    return [&lines, &names, mine](const Stage& s, std::int64_t k, const EquilibriumMeasures&) {
      lines[mine].push_back(k);
      if (lines[mine].size() == 1) names.push_back(s.name);
    };
  };
  int trials = 0;
  control.trial_done = [&](const StabilityTrial&) { ++trials; };
  const DriveResult d =
      drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), {}, control, {});
  EXPECT_EQ(d.status, RunStatus::completed);
  ASSERT_GE(trials, 3);
  ASSERT_EQ(static_cast<int>(lines.size()), trials);
  ASSERT_EQ(static_cast<int>(names.size()), trials);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].front(), sc.stages[2].check_interval) << names[i];
    EXPECT_EQ(names[i].rfind("srm F = ", 0), 0u) << names[i];
  }
  EXPECT_NE(names[0], names[1]);  // the two bounds first
}

// A stop inside trial `trial` (counted from 0) after its 5th step ends the search there: the
// trial is dropped, the trials before it stay, and the drive ends interrupted without a factor of
// safety.
void expect_stop_inside_trial(int trial) {
  const Scenario sc = parse_scenario(strength_reduction_last(), "srm.toml");
  World world = build_world(sc);
  DriveControl control;
  int trials = 0, steps_in_it = 0;
  control.trial_done = [&](const StabilityTrial&) { ++trials; };
  control.in_trial = [&](int level, bool before_stage) {
    EXPECT_EQ(level, 2);
    EXPECT_TRUE(before_stage);
    return trials == trial && ++steps_in_it == 5;
  };
  Heard heard;
  const DriveResult d =
      drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), {}, control, {&heard});
  EXPECT_EQ(d.status, RunStatus::interrupted);
  EXPECT_EQ(d.level, 2);
  EXPECT_EQ(trials, trial);
  EXPECT_EQ(steps_in_it, 5);
  const std::string after = "after " + std::to_string(trial) + " trials";
  EXPECT_NE(heard.message.find(after), std::string::npos) << heard.message;
  EXPECT_EQ(heard.events, std::vector<std::string>{"stopped 2 srm"});
}

// In the third trial (the first bisection's).
TEST(SearchBounds, AStopInsideATrialDropsTheTrialAndEndsTheSearch) {
  expect_stop_inside_trial(2);
}

// In the first trial (the lower bound's): the search ends with no trial at all.
TEST(SearchBounds, AStopInsideTheFirstTrialEndsTheSearchWithNoTrial) {
  expect_stop_inside_trial(0);
}

// A caller of the library that passes no callbacks (no progress or set-up lines) stops a run in
// its tilt stage and restarts it from the checkpoint: the outputs are those of the run never
// stopped (bytes; the summary but for its wall time).
TEST(SearchBounds, ARestartWithoutCallbacksEndsAsTheRunNeverStopped) {
  const Scenario sc = parse_scenario(test::incline_scenario(30, 40, 0.1, 0.02, ""), "tilt.toml");
  const auto fresh = test::run_folder("no_callbacks_fresh");
  const auto out = test::run_folder("no_callbacks");
  std::filesystem::remove_all(fresh);
  std::filesystem::remove_all(out);
  RunControl control;
  control.fingerprint.whole = 7;
  const RunResult whole = run_scenario(sc, fresh, {}, control);
  ASSERT_EQ(whole.status, RunStatus::completed) << whole.message;
  ASSERT_EQ(whole.steps_per_stage.size(), 2u);
  const std::int64_t stop_at = whole.steps_per_stage[0] + whole.steps_per_stage[1] / 2;
  control.poll = [&](std::int64_t steps, bool) { return RunPoll{steps == stop_at, false}; };
  const RunResult stopped = run_scenario(sc, out, {}, control);
  ASSERT_EQ(stopped.status, RunStatus::interrupted) << stopped.message;
  RunControl again;
  again.fingerprint.whole = 7;
  again.restart = out / kCheckpointName;
  const RunResult resumed = run_scenario(sc, out, {}, again);
  EXPECT_EQ(resumed.status, RunStatus::completed) << resumed.message;
  EXPECT_EQ(resumed.steps, whole.steps);
  test::expect_same_outputs(fresh, out);
}

TEST(SearchBounds, AStoppedStrengthReductionIsInterruptedAndItsRestartFindsTheSameFactor) {
  const std::string text = strength_reduction_last();
  const Scenario sc = parse_scenario(text, "srm.toml");
  const auto fresh = test::run_folder("search_stop_fresh");
  const auto out = test::run_folder("search_stop");
  std::filesystem::remove_all(fresh);
  std::filesystem::remove_all(out);
  const RunResult whole = run_scenario(sc, fresh);
  ASSERT_TRUE(whole.factor_of_safety);

  // The caller's poll: stop at its second call at the strength reduction's step count (the
  // world's steps stand still during a search): the first is at the stage's boundary, the
  // second after the first step of the first trial, which is dropped.
  ASSERT_EQ(whole.steps_per_stage.size(), 3u);
  const std::int64_t at_search = whole.steps_per_stage[0] + whole.steps_per_stage[1];
  RunControl control;
  control.fingerprint.whole = 42;
  int calls_there = 0;
  control.poll = [&](std::int64_t steps, bool) {
    if (steps == at_search) ++calls_there;
    return RunPoll{calls_there == 2, false};
  };
  const RunResult r = run_scenario(sc, out, {}, control);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.status, RunStatus::interrupted);
  EXPECT_EQ(r.exit_code, 130);
  EXPECT_NE(r.message.find("strength reduction of stage 'srm'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("--restart"), std::string::npos) << r.message;
  std::ifstream in(out / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_FALSE(summary.contains("factor_of_safety"));
  ASSERT_TRUE(std::filesystem::exists(out / kCheckpointName));

  // The checkpoint stands before the strength reduction: the restart runs it again, to the
  // factor of the run never stopped.
  RunControl again;
  again.fingerprint.whole = 42;
  again.restart = out / kCheckpointName;
  const RunResult resumed = run_scenario(sc, out, {}, again);
  ASSERT_TRUE(resumed.factor_of_safety) << resumed.message;
  EXPECT_EQ(*resumed.factor_of_safety, *whole.factor_of_safety);
}

// A real SIGINT to `blockdem run` while its strength reduction bisects (the signal is sent once
// the first trial's line is on stderr; with a bracket of 0.001 about a dozen trials follow):
// the search stops in the trial that is running, with exit code 130, status interrupted and a
// checkpoint. Before, the signal waited for the search's end and was lost in the last stage.
TEST(SearchBounds, SigintStopsTheSearchBetweenTrials) {
  const auto dir = test::run_folder("search_sigint");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scenario = dir / "srm.toml";
  std::ofstream(scenario) << strength_reduction_last("0.001");
  const auto out = dir / "out";
  const auto err = dir / "err.txt";
  std::vector<std::string> args = {BLOCKDEM_CLI_PATH, "run",        scenario.string(),
                                   "--out",           out.string(), "--no-figures"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const auto start = std::chrono::steady_clock::now();
  auto waited = [&] {
    return std::chrono::steady_clock::now() - start > std::chrono::seconds(120);
  };
  auto stderr_has = [&](const std::string& text) {
    std::ifstream in(err);
    const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return s.find(text) != std::string::npos;
  };
  while (!stderr_has("  trial ") && !waited())
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, SIGINT);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (waited()) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      FAIL() << "the run did not stop";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_TRUE(stderr_has("interrupted in the strength reduction of stage 'srm'"));
  const auto summary = nlohmann::json::parse(read_file_bytes(out / "summary.json"));
  EXPECT_EQ(summary.at("status"), "interrupted");
  EXPECT_EQ(summary.at("stages").back().at("status"), "interrupted");
  EXPECT_TRUE(std::filesystem::exists(out / kCheckpointName));
}

}  // namespace blockdem::search_bounds_test
