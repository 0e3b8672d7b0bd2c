// Outputs of the stability searches of a run: one CSV row per trial, the failure mechanism (VTK
// and a CSV of the moving blocks), and the summary.json entries.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "blockdem/world/stability.hpp"

namespace blockdem {

/// Writes `<name>.csv` (one row per trial: parameter, stable, outcome, steps, displacement,
/// speed, energies) into `dir`. `parameter` names the first column, with its unit.
void write_trials_csv(const std::filesystem::path& path, const std::string& parameter,
                      const StabilitySearch& search);

/// Writes the failed trial's mechanism: vtk/<stem>.vtk (blocks with displacement and velocity)
/// and <stem>.csv (one row per free block: displacement and velocity, moving or not).
void write_mechanism(const std::filesystem::path& dir, const std::string& stem,
                     const StabilitySearch& search, bool vtk);

/// The trials as a JSON array for summary.json.
nlohmann::json trials_json(const StabilitySearch& search);

}  // namespace blockdem
