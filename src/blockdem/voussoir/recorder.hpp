// Voussoir-beam outputs per load level: history.csv, blocks.csv, joints.csv, and the JSON
// summary.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "blockdem/io/csv.hpp"
#include "blockdem/voussoir/measures.hpp"

namespace blockdem {

class VoussoirRecorder {
 public:
  VoussoirRecorder(const std::filesystem::path& dir, const World& world);
  /// Records one level; `converged` and `steps` come from the stage.
  void record(const World& world, const VoussoirLevel& level, const std::string& stage,
              bool converged, std::int64_t steps, int index);
  const std::vector<VoussoirLevel>& levels() const { return levels_; }

 private:
  std::unique_ptr<CsvWriter> history_, blocks_, joints_;
  std::vector<VoussoirLevel> levels_;
};

/// JSON of one fit (parameters, RMS in mm, implied thrust in N).
nlohmann::json fit_json(const VoussoirLevel& level);
/// The voussoir part of summary.json: g_max (last stable level), thrust_N and
/// midspan_deflection_mm at it, equilibrium_residual (largest over levels), fits, per-level arrays.
nlohmann::json voussoir_summary(const VoussoirSpec& spec,
                                const std::vector<VoussoirLevel>& stable_levels);

}  // namespace blockdem
