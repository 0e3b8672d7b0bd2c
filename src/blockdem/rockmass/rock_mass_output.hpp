// Outputs of `blockdem generate`: the cut blocks as VTK (with the tag of every face), blocks.csv,
// and rock_mass.json (counts, volumes, block size distribution, joint sets, excavations).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "blockdem/rockmass/rock_mass_model.hpp"

namespace blockdem {

/// The summary that rock_mass.json holds.
nlohmann::json rock_mass_summary(const RockMassModel& model);

/// Writes blocks.vtk, faces.csv, blocks.csv and rock_mass.json into `out` (created if
/// missing), formatted on `threads` threads (0: OpenMP's default; the bytes are the same for any
/// number). Throws std::runtime_error when a file cannot be written.
void write_rock_mass(const RockMassModel& model, const std::filesystem::path& out, int threads = 0);

}  // namespace blockdem
