// What a restart file holds beyond its envelope: where the run stands (stage, steps into it,
// the stage's motion monitor), the world's state, the summary so far and the files written so
// far, byte for byte (docs/restart.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "blockdem/world/stage.hpp"

namespace blockdem {

struct RunPoint {
  int level = 0;          ///< the stage to run or continue (0-based)
  bool in_stage = false;  ///< the stage has started: continue it from `stage`
  StageResume stage;
  std::string monitor;  ///< the stage's MotionMonitor::save_state bytes (in_stage)
  std::string world;    ///< World::save_state bytes
  /// A collapse-search stage's starting state (World::save_state bytes), empty when none.
  std::string before;
  std::string summary;  ///< summary.json so far (JSON text)
  std::string stages;   ///< the stages' entries so far (JSON text)
  std::vector<std::int64_t> steps_per_stage;
  std::optional<double> factor_of_safety;
  /// The run's files so far: path relative to the output folder, content.
  std::vector<std::pair<std::string, std::string>> files;
  /// The writers that continue files (time_history.csv, the VTK frame lists): their state bytes.
  std::string outputs;
};

std::string encode_run_point(const RunPoint& point);
/// encode_run_point's bytes before and after the world's state (`point.world` is not read): the
/// encoding is head, the world's length (8 bytes) and bytes, tail. For a writer that streams the
/// world's state into the file as it comes (a distributed run's, docs/restart.md).
std::pair<std::string, std::string> encode_run_point_around_world(const RunPoint& point);
/// Throws StateError for bytes that are not a RunPoint. The world's state is taken out of
/// `bytes` (pass them moved: a large world's state is then never copied).
RunPoint decode_run_point(std::string bytes);
/// The same over bytes it does not own, without copying the world's states: `point.world` and
/// `point.before` stay empty, and `world` and `before` view their bytes in `bytes`.
RunPoint decode_run_point(std::string_view bytes, std::string_view& world,
                          std::string_view& before);

}  // namespace blockdem
