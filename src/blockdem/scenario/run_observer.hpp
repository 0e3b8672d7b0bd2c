// What a run tells its observers: the end of each stage, the stability searches, a stop, and the
// run's end. The run's output writer is one observer; a scene builder hands in its own
// (BuiltScene::observer), e.g. the voussoir beam's recorder.
#pragma once

#include <exception>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "blockdem/scenario/run_status.hpp"
#include "blockdem/world/stability.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/state_stream.hpp"

namespace blockdem {

/// How one stage that ran ended (not a strength reduction, not one the caller stopped).
struct StageEnd {
  const Stage& stage;
  int level = 0;  ///< index of the stage (0-based)
  const StageResult& result;
  /// The stage blew up (World::step threw `error`, a DivergenceError): the world is past its last
  /// good state and is not recorded.
  bool diverged = false;
  std::exception_ptr error;
  /// How the stage failed; empty when it converged.
  std::optional<FailureKind> failure;
  /// A failure explained in plain words, with advice (explain_failure).
  std::string explanation;

  /// The result's message, followed by the explanation of a failure.
  std::string message() const {
    return failure ? result.message + ". " + explanation : result.message;
  }
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// Whether on_stage_end reads the whole world after `stage` (a world spread over processes is
  /// completed for it, on every process alike).
  virtual bool reads_world_at_stage_end(const Stage&) const { return false; }
  /// Just before `stage` runs (also when a restart continues it part way).
  virtual void on_stage_start(const World&, const Stage&, int /*level*/) {}
  virtual void on_stage_end(const World&, const StageEnd&) {}
  /// A strength-reduction stage: its search, and the stage's result (the trials' steps summed;
  /// the world is left as it was before the stage).
  virtual void on_strength_reduction(const World&, const Stage&, int /*level*/,
                                     const StabilitySearch&, const StageResult&) {}
  /// The collapse search that followed the failure of `stage` (reported by on_stage_end).
  virtual void on_collapse_search(const Stage&, int /*level*/, const StabilitySearch&) {}
  /// The caller stopped the run: in `stage` after `result->steps` steps, or before the stage
  /// started when `result` is null.
  virtual void on_interrupted(const World&, const Stage&, int /*level*/, const StageResult*) {}
  /// An input error found only while running `stage` (strength-reduction bounds that do not
  /// bracket the failure): the run stops there, keeping what it wrote (`message`: file, key and
  /// reason).
  virtual void on_input_error(const World&, const Stage&, int /*level*/,
                              const std::string& /*message*/) {}
  /// Added to the message of a run that failed (e.g. the last stable load level).
  virtual std::string failure_note() const { return {}; }
  /// Adds the observer's entries to summary.json when the run ends with `status`.
  virtual void add_to_summary(nlohmann::json&, RunStatus) const {}
  /// The run has written its last file: the observer closes its files (what it measured stays).
  virtual void on_run_end() {}
  /// What the observer has measured so far, for a checkpoint (its files are saved with the run's).
  virtual void save_state(StateWriter&) const {}
  /// A restart: what save_state wrote (throws StateError for bytes it cannot read).
  virtual void load_state(StateReader&) {}
};

}  // namespace blockdem
