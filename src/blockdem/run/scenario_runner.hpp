// Runs a scenario's stages and writes every output of a run into one folder;
// shared by `blockdem run` and `blockdem reproduce`.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/run/scenario_fingerprint.hpp"
#include "blockdem/scenario/run_observer.hpp"
#include "blockdem/scenario/scenario.hpp"

namespace blockdem {

class MappedCheckpoint;

struct RunResult {
  /// completed, collapsed (physical: a mechanism formed), diverged (numerical blow-up),
  /// not_converged (no equilibrium and no mechanism within the step limit), interrupted
  /// (RunControl::poll asked the run to stop); failed is set by callers whose run threw (a
  /// study's case).
  RunStatus status = RunStatus::completed;
  std::string message;
  /// 0 completed, or collapsed with a collapse search asked for (the search found it);
  /// 130 interrupted (the caller maps it to its signal); 3 otherwise.
  int exit_code = 0;
  bool interrupted = false;
  /// Files in the output folder that the run did not write (there before it): not in
  /// summary.json's "files".
  std::set<std::string> foreign_files;
  std::optional<std::pair<double, double>> collapse;  ///< last stable, first failed (g)
  std::optional<double> factor_of_safety;             ///< of the last strength_reduction stage
  nlohmann::json summary;                             ///< what summary.json holds
  /// The observer the scene handed in (BuiltScene::observer), for the caller to read what it
  /// measured; null when the scene has none.
  std::shared_ptr<const RunObserver> scene_output;
  std::vector<std::int64_t> steps_per_stage;
  std::int64_t steps = 0;
  double wall_time = 0.0;  ///< (s)
  /// With RunControl::report_memory: this process's peak resident memory up to the end of the
  /// set-up (reading the scene, building the world, loading a checkpoint) (B); -1 otherwise.
  std::int64_t set_up_peak_memory = -1;
  /// With RunControl::report_memory: its resident memory at the end of the set-up, with what
  /// was read to build the world freed (B); -1 otherwise.
  std::int64_t set_up_memory = -1;
};

struct RunCallbacks {
  /// Status line while a stage runs (may be called often).
  std::function<void(const std::string&)> progress;
  /// One line when a stage ends.
  std::function<void(const std::string&)> stage_done;
  /// One line when a part of the set-up that took at least a second ends (the world built from
  /// the scenario's blocks, a checkpoint loaded), with its wall time: a large scene spends tens
  /// of seconds there, before the first status line.
  std::function<void(const std::string&)> setup_done;
  /// The block that sets the time step, once, before the first step (time_step_report.hpp);
  /// `warning`: the line is a warning (an outlier block).
  std::function<void(const std::string&, bool warning)> time_step;
};

/// What a run does after a step or between stages: stop, and write a timed checkpoint.
struct RunPoll {
  bool stop = false;        ///< stop here: checkpoint, outputs so far, status "interrupted"
  bool checkpoint = false;  ///< write the timed checkpoint (--checkpoint-seconds) now
};

/// Checkpoints, restarts and stopping (docs/restart.md).
struct RunControl {
  std::int64_t checkpoint_every = 0;  ///< world steps between checkpoints (0: none)
  double checkpoint_seconds = 0.0;    ///< wall time between checkpoints (s); 0: none
  /// Continue the run saved in this checkpoint (empty: a fresh run).
  std::filesystem::path restart;
  /// The payload of `restart`, already read and checked (read_checkpoint_file) by one process
  /// of an MPI run and sent to the others; null: the runner reads `restart` itself. The runner
  /// moves the bytes out (they hold a large world's state, which is then not kept twice).
  std::shared_ptr<std::string> restart_payload;
  /// `restart`, already mapped and checked by this process (each process of an MPI run that
  /// sees the file maps it itself); null: see restart_payload. The runner loads the world from
  /// it in place and releases it once loaded.
  std::shared_ptr<MappedCheckpoint> restart_file;
  /// Identifies the scenario and the options that change results, up to each stage: a
  /// checkpoint is accepted when the scenario agrees with the run that wrote it up to the
  /// checkpoint's stage (later stages may differ: a branch), refused otherwise.
  ScenarioFingerprint fingerprint;
  /// The hash carried by the checkpoint in `restart_payload` (its envelope was checked by the
  /// process that read it).
  std::uint64_t restart_hash = 0;
  /// Polled after every step of a stage and between stages, with the world's step count and
  /// whether this process's wall clock says a timed checkpoint is due. Its answer is what the
  /// run does. Every process of an MPI run calls it at the same points, so that the caller can
  /// make the answer the same on all of them (one reduction: every process stops after the same
  /// step and takes the same checkpoints). Empty: never stop; the local clock decides.
  std::function<RunPoll(std::int64_t steps, bool checkpoint_due)> poll;
  /// False on the processes of an MPI run that do not write the outputs: they take every
  /// checkpoint decision but write no checkpoint file.
  bool write_checkpoint_files = true;
  /// The output folder every process of an MPI run shares, when `out` is this process's own
  /// (the processes that do not write the outputs): each process writes its VTK pieces into
  /// its vtk/ (docs/outputs.md). Empty: `out`.
  std::filesystem::path shared_out;
  /// Keep the set-up's peak resident memory in RunResult::set_up_peak_memory and start the
  /// process's peak again once the world is built (restart_peak), so that the peak at the end
  /// is the run's own (bench/memory_ranks.sh). Tools that read the process's peak then see only
  /// the run's.
  bool report_memory = false;
};

/// Builds the world, runs every stage, and writes history.csv, blocks.csv, contacts.csv (and
/// joints.csv for a voussoir beam), summary.json and vtk/ into `out`. A stage that does not
/// converge or diverges ends the run: the outputs up to the last good state are kept and
/// summary.json (written last) says what happened and lists the run's files. Throws
/// ScenarioError for input errors found while building, CheckpointError for an unusable restart
/// file (both before anything is written).
RunResult run_scenario(const Scenario& scenario, const std::filesystem::path& out,
                       const RunCallbacks& callbacks = {}, const RunControl& control = {});
/// The same, moving the scenario's blocks into the world instead of copying them (the scenario
/// is left without blocks; nothing else in it changes): a large scene holds its blocks once.
RunResult run_scenario(Scenario&& scenario, const std::filesystem::path& out,
                       const RunCallbacks& callbacks = {}, const RunControl& control = {});

}  // namespace blockdem
