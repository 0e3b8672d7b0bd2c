// Writes a run's results as it goes: history.csv (one row per stage end), blocks.csv and
// contacts.csv (one row per stage end and block/contact), and VTK files.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "blockdem/io/csv.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

class RunRecorder {
 public:
  /// Creates `dir` if needed. Throws std::runtime_error when it cannot be written.
  /// `tables`: write history.csv and blocks.csv (a voussoir run writes its own instead).
  /// `append`: the files exist with the rows of a run being restarted; add to them.
  RunRecorder(const std::filesystem::path& dir, bool vtk, bool tables = true, bool append = false);

  /// Records the world at the end of stage `level` (0-based).
  void record(const World& world, const StageResult& stage, int level);

  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  bool vtk_ = true;
  std::unique_ptr<CsvWriter> history_, blocks_, contacts_;
};

}  // namespace blockdem
