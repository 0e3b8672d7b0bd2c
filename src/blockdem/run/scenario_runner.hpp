// Runs a scenario's stages and writes every output of a run into one folder;
// shared by `blockdem run` and `blockdem reproduce`.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/scenario/scenario.hpp"
#include "blockdem/voussoir/measures.hpp"

namespace blockdem {

struct RunResult {
  /// "completed", "collapsed" (physical: a mechanism formed), "diverged" (numerical blow-up),
  /// "not_converged" (no equilibrium and no mechanism within the step limit).
  std::string status = "completed";
  std::string message;
  /// 0 completed, or collapsed with a collapse search asked for (the search found it);
  /// 3 otherwise.
  int exit_code = 0;
  std::optional<std::pair<double, double>> collapse;  ///< last stable, first failed (g)
  std::optional<double> factor_of_safety;             ///< of the last strength_reduction stage
  nlohmann::json summary;                             ///< what summary.json holds
  std::vector<VoussoirLevel> levels;  ///< voussoir runs: the converged levels, preload first
  std::vector<std::int64_t> steps_per_stage;
  std::int64_t steps = 0;
  double wall_time = 0.0;  ///< (s)
};

struct RunCallbacks {
  /// Status line while a stage runs (may be called often).
  std::function<void(const std::string&)> progress;
  /// One line when a stage ends.
  std::function<void(const std::string&)> stage_done;
};

/// Builds the world, runs every stage, and writes history.csv, blocks.csv, contacts.csv (and
/// joints.csv for a voussoir beam), summary.json and vtk/ into `out`. A stage that does not
/// converge or diverges ends the run: the outputs up to the last good state are kept and
/// summary.json says what happened. Throws ScenarioError for input errors found while building
/// (before anything is written).
RunResult run_scenario(const Scenario& scenario, const std::filesystem::path& out,
                       const RunCallbacks& callbacks = {});

}  // namespace blockdem
