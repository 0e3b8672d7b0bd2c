// Voussoir-beam outputs per load level: history.csv, blocks.csv, joints.csv, and the JSON
// summary; the run observer the voussoir scene hands in.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "blockdem/io/csv.hpp"
#include "blockdem/scenario/run_observer.hpp"
#include "blockdem/voussoir/measures.hpp"

namespace blockdem {

class VoussoirRecorder final : public RunObserver {
 public:
  /// `resumed`: the run continues a checkpoint; the files are back in `dir` and the recorder
  /// appends to them (load_state then gives it the levels measured before).
  VoussoirRecorder(const std::filesystem::path& dir, VoussoirSpec spec, VoussoirLayout layout,
                   bool resumed = false);
  /// Records one level; `converged` and `steps` come from the stage.
  void record(const World& world, const VoussoirLevel& level, const std::string& stage,
              bool converged, std::int64_t steps, int index);
  const std::vector<VoussoirLevel>& levels() const { return levels_; }
  /// The levels whose stage converged, preload first.
  const std::vector<VoussoirLevel>& stable_levels() const { return stable_; }

  /// The beam's measures at every stage end read the whole world.
  bool reads_world_at_stage_end(const Stage&) const override { return true; }
  /// Measures and records the level (the first stage's end is the reference of displacements);
  /// a diverged stage is not recorded.
  void on_stage_end(const World& world, const StageEnd& end) override;
  /// "; last stable level G g" when a level converged.
  std::string failure_note() const override;
  /// summary.json's "voussoir", its headline numbers at the top level, and "lost_equilibrium".
  void add_to_summary(nlohmann::json& summary, RunStatus status) const override;
  /// Closes the CSV files (the levels stay).
  void on_run_end() override;
  /// The reference pose and every level measured so far (the CSV rows are in the run's files).
  void save_state(StateWriter& w) const override;
  void load_state(StateReader& r) override;

 private:
  VoussoirSpec spec_;
  VoussoirLayout layout_;
  VoussoirReference reference_;
  std::unique_ptr<CsvWriter> history_, blocks_, joints_;
  std::vector<VoussoirLevel> levels_, stable_;
};

/// JSON of one fit (parameters, RMS in mm, implied thrust in N).
nlohmann::json fit_json(const VoussoirLevel& level);
/// The voussoir part of summary.json: g_max (last stable level), thrust_N and
/// midspan_deflection_mm at it, equilibrium_residual (largest over levels), fits, per-level arrays.
nlohmann::json voussoir_summary(const VoussoirSpec& spec,
                                const std::vector<VoussoirLevel>& stable_levels);

}  // namespace blockdem
