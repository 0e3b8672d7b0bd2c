// The stage driver: every observer hears of every stage in order, a stop at a boundary ends the
// drive there, and `blockdem run`'s runner (its oracle here) took the same steps; the names of
// the run statuses and contact modes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../validation/stability_support.hpp"
#include "blockdem/run/stage_driver.hpp"
#include "blockdem/world/contact_mode.hpp"

namespace blockdem::stage_driver_test {

/// What an observer heard, in order.
struct Heard final : RunObserver {
  std::vector<std::string> events;
  std::vector<std::int64_t> steps;

  void on_stage_start(const World&, const Stage& stage, int level) override {
    events.push_back("start " + std::to_string(level) + " " + stage.name);
  }
  void on_stage_end(const World&, const StageEnd& end) override {
    events.push_back("end " + std::to_string(end.level) + " " + end.stage.name);
    steps.push_back(end.result.steps);
  }
  void on_interrupted(const World&, const Stage& stage, int level,
                      const StageResult* result) override {
    events.push_back(std::string(result ? "stopped in " : "stopped before ") +
                     std::to_string(level) + " " + stage.name);
  }
};

std::string incline() {
  return test::incline_scenario(20, 40, 0.1, 0.02, "");
}

TEST(StageDriver, EveryObserverHearsEveryStageInOrder) {
  const Scenario sc = parse_scenario(incline(), "incline.toml");
  World world = build_world(sc);
  Heard first, second;
  const DriveResult d =
      drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), {}, {}, {&first, &second});
  EXPECT_EQ(d.status, RunStatus::completed);
  EXPECT_EQ(d.level, -1);
  const std::vector<std::string> expected = {"start 0 settle", "end 0 settle", "start 1 tilt",
                                             "end 1 tilt"};
  EXPECT_EQ(first.events, expected);
  EXPECT_EQ(second.events, expected);
  EXPECT_EQ(first.steps[0] + first.steps[1], world.step_count());
  // The runner of `blockdem run` drives the same stages to the same step counts.
  const RunResult r = test::run_text(incline(), "stage_driver_incline");
  EXPECT_EQ(r.status, RunStatus::completed);
  EXPECT_EQ(r.steps_per_stage, first.steps);
}

TEST(StageDriver, AStopAtABoundaryEndsTheDriveBeforeTheStage) {
  const Scenario sc = parse_scenario(incline(), "incline.toml");
  World world = build_world(sc);
  Heard heard;
  DriveControl control;
  control.at_boundary = [](int level) { return level == 1; };
  const DriveResult d =
      drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), {}, control, {&heard});
  EXPECT_EQ(d.status, RunStatus::interrupted);
  EXPECT_EQ(d.level, 1);
  EXPECT_TRUE(d.before_stage);
  const std::vector<std::string> expected = {"start 0 settle", "end 0 settle",
                                             "stopped before 1 tilt"};
  EXPECT_EQ(heard.events, expected);
  EXPECT_EQ(heard.steps[0], world.step_count());
}

TEST(StageDriver, AStopAfterAStepEndsTheStageThere) {
  const Scenario sc = parse_scenario(incline(), "incline.toml");
  World world = build_world(sc);
  Heard heard;
  DriveControl control;
  control.after_step = [](int, const StageResume& at, const MotionMonitor&, const World*) {
    return at.steps_done == 25;
  };
  const DriveResult d =
      drive_stages(world, sc.stages, static_cast<int>(sc.stages.size()), {}, control, {&heard});
  EXPECT_EQ(d.status, RunStatus::interrupted);
  EXPECT_FALSE(d.before_stage);
  EXPECT_EQ(d.stage.steps, 25);
  EXPECT_EQ(world.step_count(), 25);
  const std::vector<std::string> expected = {"start 0 settle", "stopped in 0 settle"};
  EXPECT_EQ(heard.events, expected);
}

TEST(RunStatusNames, AreTheWordsOfSummaryJson) {
  EXPECT_STREQ(to_string(RunStatus::completed), "completed");
  EXPECT_STREQ(to_string(RunStatus::collapsed), "collapsed");
  EXPECT_STREQ(to_string(RunStatus::diverged), "diverged");
  EXPECT_STREQ(to_string(RunStatus::not_converged), "not_converged");
  EXPECT_STREQ(to_string(RunStatus::interrupted), "interrupted");
  EXPECT_STREQ(to_string(RunStatus::failed), "failed");
  // A failed stage's status is its failure's word.
  for (FailureKind kind :
       {FailureKind::collapsed, FailureKind::diverged, FailureKind::not_converged})
    EXPECT_STREQ(to_string(run_status(kind)), to_string(kind));
}

TEST(ContactModeNames, ReadBackWhatToStringWrites) {
  for (ContactMode mode : kContactModes) EXPECT_EQ(parse_contact_mode(to_string(mode)), mode);
  EXPECT_FALSE(parse_contact_mode("both").has_value());
  EXPECT_FALSE(parse_contact_mode("").has_value());
  EXPECT_EQ(contact_mode_names(), (std::vector<std::string>{"boon2012", "face_integrated"}));
  EXPECT_EQ(contact_modes_selected("both"),
            (std::vector<ContactMode>{ContactMode::boon2012, ContactMode::face_integrated}));
  EXPECT_EQ(contact_modes_selected("face_integrated"),
            std::vector<ContactMode>{ContactMode::face_integrated});
  EXPECT_TRUE(contact_modes_selected("neither").empty());
}

}  // namespace blockdem::stage_driver_test
