// What one step carries from pass to pass (world/step.cpp): the time step, the threads and, for a
// distributed step, the blocks and pairs of this process and the figures it reduces.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

namespace blockdem {

/// A one-process step leaves the distributed part empty; a distributed step fills it in
/// Decomposition::begin_step.
struct StepScratch {
  double dt = 0.0;  ///< this step's time step (s)
  int threads = 1;  ///< threads of this process
  bool distributed = false;
  /// The blocks exact on this process (own, resting, ghosts), in index order, and their boxes
  /// (the broad phase's input); per block, whether it is dynamic (read per pair).
  std::vector<int> held;
  std::vector<Eigen::Vector3d> held_min, held_max;
  std::vector<char> moves;
  /// The slots this process evaluates (indices, and per slot a flag).
  std::vector<std::int64_t> mine;
  std::vector<char> is_mine;
  /// Every process's pair time and count, gathered after the pair pass (rebalancing).
  double slowest = 0.0, total = 0.0, most_pairs = 0.0, total_pairs = 0.0;
  double pair_seconds = 0.0;  ///< this process's own pair work (s)
  double waiting = 0.0;       ///< time in the exchanges and reductions, waiting included (s)
  std::int64_t broken_before = 0, active = 0, broke = 0;
  double overlap_key = std::numeric_limits<double>::infinity();
  double dt_min = std::numeric_limits<double>::infinity();
};

}  // namespace blockdem
