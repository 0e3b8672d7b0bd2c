// Writes a run's results as it goes: history.csv (one row per stage end), blocks.csv and
// contacts.csv (one row per stage end and block/contact), and VTK frames with .pvd collections.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "blockdem/io/csv.hpp"
#include "blockdem/io/vtu.hpp"
#include "blockdem/world/stage.hpp"
#include "blockdem/world/state_stream.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

class RunRecorder {
 public:
  /// Creates `dir` if needed. Throws std::runtime_error when it cannot be written.
  /// `tables`: write history.csv and blocks.csv (a voussoir run writes its own instead).
  /// `append`: the files exist with the rows of a run being restarted; add to them.
  /// `pieces`: the folder shared by the processes of a distributed run where each writes its VTK
  /// pieces (the output folder's vtk/; empty: dir/vtk); see write_frame.
  RunRecorder(const std::filesystem::path& dir, bool vtk, bool tables = true, bool append = false,
              std::filesystem::path pieces = {});

  /// Records the world at the end of stage `level` (0-based): every row at the world's level
  /// state (World::level_state), and a VTK frame.
  void record(const World& world, const StageResult& stage, int level);
  /// Writes vtk/blocks_NNNNNN.vtu and vtk/contacts_NNNNNN.vtu at the world's level and adds them
  /// to vtk/blocks.pvd and vtk/contacts.pvd with their model time (no-op without VTK output).
  /// A world spread over more than one process writes instead, on every process K, the pieces
  /// blocks_NNNNNN_pK.vtu and contacts_NNNNNN_pK.vtu of the blocks and pairs K owns, then
  /// process 0 the indices blocks_NNNNNN.pvtu and contacts_NNNNNN.pvtu, which the .pvd files
  /// list. Collective then: every process calls it at the same steps, on a whole world (the
  /// contacts are read with World::contacts()).
  void write_frame(const World& world, int level);

  const std::filesystem::path& dir() const { return dir_; }

  /// The VTK frames written so far (count, last step, the .pvd lists), for a restart.
  void save_state(StateWriter& w) const;
  /// Throws StateError for bytes that are not a recorder's state.
  void load_state(StateReader& r);

 private:
  std::filesystem::path dir_;
  std::filesystem::path pieces_;
  bool vtk_ = true;
  std::unique_ptr<CsvWriter> history_, blocks_, contacts_;
  std::unique_ptr<PvdCollection> blocks_pvd_, contacts_pvd_;
  int frames_ = 0;
  std::int64_t last_frame_step_ = -1;
};

}  // namespace blockdem
