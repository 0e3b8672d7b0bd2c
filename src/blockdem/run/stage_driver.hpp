// The stage loop shared by `blockdem run` and Python's Simulation.run_stage: runs the stages,
// the strength reductions and the collapse search, and reports every stage's end to observers.
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/scenario/run_observer.hpp"

namespace blockdem {

/// Where a drive starts: at a stage's start, or part way into it (a restart).
struct DriveStart {
  int level = 0;
  /// The stage at `level` continues from here (null: it starts afresh).
  const StageResume* resume = nullptr;
  std::optional<MotionMonitor> monitor;  ///< the stage's monitor then (with resume)
  std::optional<World> before;           ///< the world before the stage, for its collapse search
};

/// What the caller does between steps and stages; every member may be empty.
struct DriveControl {
  /// At the boundary before stage `level` starts (not when a restart continues it): returns
  /// true to stop the run there.
  std::function<bool(int level)> at_boundary;
  /// After every step of stage `level` (before: the world before the stage, when a search
  /// needs it): returns true to stop the stage there.
  std::function<bool(int level, const StageResume& at, const MotionMonitor& monitor,
                     const World* before)>
      after_step;
  /// After every step, e.g. a time-history writer (run_stage's StepFn).
  std::function<void(const World&, const Stage&, int level)> on_step;
  /// Progress reports of stage `level` (run_stage's ProgressFn).
  std::function<ProgressFn(int level)> progress;
  /// After each trial of a stability search.
  TrialFn trial_done;
  /// Between two trials of a stability search of stage `level`: returns true to stop the run
  /// there. `before_stage`: nothing of the stage is recorded yet (a strength reduction, whose
  /// outputs come at its end), so that the stage may be run again from its start.
  std::function<bool(int level, bool before_stage)> between_trials;
  /// After every step of a trial of such a search (arguments as between_trials): returns true
  /// to stop the run there; the trial is dropped, as if the stop had come before it.
  std::function<bool(int level, bool before_stage)> in_trial;
  /// Handed to run_stage (a world spread over processes); null: run_stage's default.
  const StageSync* sync = nullptr;
  /// Search for the collapse after any failure that World::step did not throw, also one
  /// classified as numerical (Python's Simulation.run_stage); else not after a divergence.
  bool search_after_any_failure = false;
};

/// How a drive ended.
struct DriveResult {
  RunStatus status = RunStatus::completed;
  int level = -1;     ///< the stage that ended the run early (-1: it ran to the end)
  StageResult stage;  ///< that stage's result; a failure's message ends with its explanation
  bool before_stage = false;  ///< stopped at the boundary before `level` started
  /// The collapse bracket (last stable, first failed; g) of a collapse search.
  std::optional<std::pair<double, double>> collapse;
};

/// A strength reduction whose bounds were unusable: what std::invalid_argument said ("KEY:
/// reason"), and the stage.
struct StrengthReductionError : std::invalid_argument {
  StrengthReductionError(int stage_level, const std::string& what)
      : std::invalid_argument(what), level(stage_level) {}
  int level = 0;  ///< index of the stage (0-based)
};

/// Runs stages[start.level] up to stages[end - 1] on `world`. A stage that fails ends the drive
/// (after its collapse search, when it asks for one); a stop asked for by `control` ends it with
/// RunStatus::interrupted. Every process of a distributed world calls it alike. Throws what
/// run_stage throws but DivergenceError (reported to the observers as StageEnd::error), and
/// StrengthReductionError.
DriveResult drive_stages(World& world, const std::vector<Stage>& stages, int end, DriveStart start,
                         const DriveControl& control, const std::vector<RunObserver*>& observers);

}  // namespace blockdem
