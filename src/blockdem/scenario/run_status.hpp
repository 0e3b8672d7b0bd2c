// How a run (or one stage of it) ended: one enum, and the word every output file uses for it.
#pragma once

#include <string>

#include "blockdem/world/motion_monitor.hpp"

namespace blockdem {

enum class RunStatus {
  completed,      ///< every stage converged (or ran its steps)
  collapsed,      ///< physical: a mechanism formed
  diverged,       ///< numerical blow-up
  not_converged,  ///< no equilibrium and no mechanism within the step limit
  interrupted,    ///< the caller asked the run to stop
  failed,         ///< the run threw before it ended (a study's case)
  input_error,    ///< an input error found only while running (the outputs so far are kept)
};

/// The word summary.json, reports and messages use ("completed", "not_converged", ...).
constexpr const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed:
      return "completed";
    case RunStatus::collapsed:
      return "collapsed";
    case RunStatus::diverged:
      return "diverged";
    case RunStatus::not_converged:
      return "not_converged";
    case RunStatus::interrupted:
      return "interrupted";
    case RunStatus::failed:
      return "failed";
    case RunStatus::input_error:
      return "input_error";
  }
  return "failed";
}

/// The run status of a stage that failed this way.
constexpr RunStatus run_status(FailureKind kind) {
  switch (kind) {
    case FailureKind::collapsed:
      return RunStatus::collapsed;
    case FailureKind::diverged:
      return RunStatus::diverged;
    case FailureKind::not_converged:
      return RunStatus::not_converged;
  }
  return RunStatus::failed;
}

}  // namespace blockdem
