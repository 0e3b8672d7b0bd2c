// A run that continues a checkpoint: the file read and checked before anything is written, and
// its states loaded into the world as built (docs/restart.md).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/io/checkpoint_file.hpp"
#include "blockdem/run/run_checkpoint.hpp"
#include "blockdem/run/scenario_runner.hpp"
#include "blockdem/run/stage_driver.hpp"

namespace blockdem {

/// The restart file of a run that continues one, read and checked before anything is written.
/// A file read by this process is mapped, not read into memory: the world's states are read in
/// place and the pages behind the reader given back, so that the file's bytes and the loaded
/// world are never both resident (a payload handed over by the caller is a string).
struct Restart {
  std::optional<RunPoint> point;
  std::shared_ptr<MappedCheckpoint> mapped;
  std::string_view world, before;  ///< the saved states, in `point` or in `mapped`
  std::string compared;            ///< what the restart compared with the scenario
};

/// Fills `r` in place (its views point into it): the checkpoint of `control.restart`, checked
/// against the scenario (its stages named `stage_names`) as far as the checkpoint reaches.
void read_restart(const RunControl& control, const std::vector<std::string>& stage_names,
                  Restart& r);

/// Loads the checkpoint's world (and, part way into a stage, its motion monitor and the world
/// before a searching stage) into `world`, as built, and `start`; the restart's bytes go.
void load_restart(Restart& restart, const Scenario& sc, World& world, const RunControl& control,
                  DriveStart& start);

}  // namespace blockdem
