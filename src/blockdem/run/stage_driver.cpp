// The stage loop: each stage run (or its strength reduction), its failure classified and
// explained, observers told, and the collapse search of a failed stage that asks for one.
#include "blockdem/run/stage_driver.hpp"

#include <memory>

#include "blockdem/numerics/units.hpp"

namespace blockdem {
namespace {

/// The caller's stop between the trials of stage `level`'s search.
StopFn search_stop(const DriveControl& control, int level, bool before_stage) {
  if (!control.between_trials) return {};
  return [&control, level, before_stage] { return control.between_trials(level, before_stage); };
}

/// The caller's stop after each step of a trial of stage `level`'s search.
StopFn trial_stop(const DriveControl& control, int level, bool before_stage) {
  if (!control.in_trial) return {};
  return [&control, level, before_stage] { return control.in_trial(level, before_stage); };
}

/// The status lines of a search's trials: each trial's as a stage's of its own (its steps from
/// 0, its rate from its start, which run_trial marks with a call at step 0).
ProgressFn trial_progress(const DriveControl& control, int level) {
  if (!control.progress) return {};
  auto current = std::make_shared<ProgressFn>();
  return [&control, level, current](const Stage& s, std::int64_t k, const EquilibriumMeasures& m) {
    if (k == 0) {
      *current = control.progress(level);  // a new trial: its clock starts now
      return;
    }
    if (*current) (*current)(s, k, m);
  };
}

/// A strength-reduction stage: the factor of safety; the world stays in the state before it.
/// Returns false when the caller stopped it between two trials (observers told: interrupted).
bool reduce_strength(const World& world, const World& before, const Stage& stage, int level,
                     const DriveControl& control, const std::vector<RunObserver*>& observers) {
  StabilitySearch search;
  try {
    search =
        strength_reduction(before, stage, laws_named(world, stage.strength.laws),
                           stage.strength.lower, stage.strength.upper, stage.strength.tolerance,
                           control.trial_done, search_stop(control, level, true),
                           trial_progress(control, level), trial_stop(control, level, true));
  } catch (const std::invalid_argument& e) {
    throw StrengthReductionError(level, e.what());
  }
  StageResult result;
  result.name = stage.name;
  result.converged = !search.interrupted;
  for (const auto& t : search.trials) result.steps += t.steps;
  result.time = world.time();
  result.measures = world.equilibrium();
  if (search.interrupted) {
    result.interrupted = true;
    result.message =
        "stopped in the strength reduction (a trial stopped part way is dropped), after " +
        std::to_string(search.trials.size()) + " trials";
    for (RunObserver* o : observers) o->on_interrupted(world, stage, level, &result);
    return false;
  }
  for (RunObserver* o : observers) o->on_strength_reduction(world, stage, level, search, result);
  return true;
}

/// One stage run: a DivergenceError ends it with the last observation before the blow-up.
struct StageRun {
  StageResult result;
  bool diverged = false;
  bool refused = false;  ///< a StepFailure: a value refused inside a step
  std::exception_ptr error;
};

StageRun run_one_stage(World& world, const Stage& stage, int level, DriveStart& start,
                       bool resuming, std::optional<MotionMonitor>& monitor,
                       const std::optional<World>& before, const DriveControl& control) {
  AfterStepFn after_step;
  if (control.after_step) {
    after_step = [&](const StageResume& at) {
      return control.after_step(level, at, *monitor, before ? &*before : nullptr);
    };
  }
  StepFn on_step;
  if (control.on_step) {
    on_step = [&](const World& w, const Stage& s, std::int64_t) { control.on_step(w, s, level); };
  }
  const ProgressFn progress = control.progress ? control.progress(level) : ProgressFn{};
  StageRun run;
  try {
    run.result = run_stage(world, stage, progress, &monitor, after_step,
                           resuming ? start.resume : nullptr, on_step, control.sync);
  } catch (const DivergenceError& e) {
    run.diverged = true;
    run.refused = dynamic_cast<const StepFailure*>(&e) != nullptr;
    run.error = std::current_exception();
    run.result.name = stage.name;
    run.result.time = world.time();
    run.result.measures = world.equilibrium();
    run.result.message = e.what();
    run.result.motion = monitor->report();
  }
  return run;
}

/// Bisects the collapse load of `stage` between the gravity of `before` and the stage's; `stopped`
/// says whether the caller stopped it between two trials (the bracket is the one so far).
std::pair<double, double> search_collapse(const World& before, const Stage& stage, int level,
                                          const DriveControl& control,
                                          const std::vector<RunObserver*>& observers,
                                          bool& stopped) {
  // A seismic search runs from k_h = 0 to the stage's (gravity stays as it was).
  const bool seismic = !stage.gravity;
  const double g_stable = seismic ? 0.0 : before.settings().gravity.norm() / kOneG;
  const double g_failed = seismic ? stage.seismic->horizontal : stage.gravity->norm() / kOneG;
  const StabilitySearch cs = find_collapse_load(
      before, stage, g_stable, g_failed, stage.collapse_tolerance, control.trial_done,
      search_stop(control, level, false), trial_stop(control, level, false));
  for (RunObserver* o : observers) o->on_collapse_search(stage, level, cs);
  stopped = cs.interrupted;
  return {cs.last_stable, cs.first_failed};
}

}  // namespace

DriveResult drive_stages(World& world, const std::vector<Stage>& stages, int end, DriveStart start,
                         const DriveControl& control, const std::vector<RunObserver*>& observers) {
  const int first = start.level;
  for (int level = first; level < end; ++level) {
    const Stage& stage = stages[level];
    const bool search = stage.find_collapse && stage.kind == Stage::Kind::equilibrium;
    const bool reduce = stage.kind == Stage::Kind::strength_reduction;
    const bool resuming = level == first && start.resume != nullptr;
    // A stage starts from the whole world (the previous stage left each process its own part:
    // the refresh that ended a stage now comes at the next one's start, and none after the last).
    world.synchronize();
    if (!resuming && control.at_boundary && control.at_boundary(level)) {
      for (RunObserver* o : observers) o->on_interrupted(world, stage, level, nullptr);
      DriveResult stopped{RunStatus::interrupted, level, {}, true, {}};
      stopped.stage.name = stage.name;
      return stopped;
    }
    // The state before the stage, from which every trial of a search starts.
    std::optional<World> before;
    if (resuming && start.before) {
      before = std::move(start.before);
    } else if (!resuming && (search || reduce)) {
      before.emplace(world);
    }
    if (reduce) {
      if (reduce_strength(world, *before, stage, level, control, observers)) continue;
      DriveResult stopped{RunStatus::interrupted, level, {}, false, {}};
      stopped.stage.name = stage.name;
      return stopped;
    }
    std::optional<MotionMonitor> monitor;
    if (resuming) monitor = std::move(start.monitor);
    for (RunObserver* o : observers) o->on_stage_start(world, stage, level);
    StageRun run = run_one_stage(world, stage, level, start, resuming, monitor, before, control);
    StageResult& result = run.result;
    if (result.interrupted) {
      for (RunObserver* o : observers) o->on_interrupted(world, stage, level, &result);
      return {RunStatus::interrupted, level, std::move(result), false, {}};
    }
    const bool failed = run.diverged || !result.converged;
    bool reads = false;
    for (const RunObserver* o : observers) reads = reads || o->reads_world_at_stage_end(stage);
    // Collective, on every process alike (a no-op on a whole world).
    if (failed || reads) world.synchronize();
    // A value refused inside a step is numerical whatever the motion before it looked like.
    const FailureKind kind = run.refused ? FailureKind::diverged
                             : failed    ? classify_failure(*monitor, run.diverged)
                                         : FailureKind::not_converged;
    const StageEnd stage_end{stage,
                             level,
                             result,
                             run.diverged,
                             run.error,
                             failed ? std::optional<FailureKind>(kind) : std::nullopt,
                             failed ? explain_failure(kind, result.motion, world) : ""};
    for (RunObserver* o : observers) o->on_stage_end(world, stage_end);
    if (!failed) continue;
    DriveResult ended{run_status(kind), level, result, false, {}};
    ended.stage.message = stage_end.message();
    if (search && (kind != FailureKind::diverged || control.search_after_any_failure)) {
      bool stopped = false;
      ended.collapse = search_collapse(*before, stage, level, control, observers, stopped);
      ended.status = stopped ? RunStatus::interrupted : RunStatus::collapsed;
    }
    return ended;
  }
  return {};
}

}  // namespace blockdem
