// The hook through which a world spreads its per-pair work over processes (MPI ranks): which
// process owns which block, and an all-gather of bytes. Implemented in parallel/ (floor 4).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace blockdem {

/// What the world needs from a group of processes that run the same scenario in lockstep. Every
/// process holds the whole world; each evaluates the contacts it owns, and the results are
/// gathered so that every process ends the step with the same, complete state.
class PairDistribution {
 public:
  virtual ~PairDistribution() = default;
  virtual int rank() const = 0;  ///< this process, in [0, size())
  virtual int size() const = 0;  ///< number of processes
  /// Owner process of each point (block centroids), with the given weights balanced over the
  /// processes. Must give the same answer on every process for the same input.
  virtual std::vector<int> partition(std::span<const Eigen::Vector3d> points,
                                     std::span<const double> weights) const = 0;
  /// > 0: partition again at least every this many steps, imbalanced or not (0: only when the
  /// measured load is uneven).
  virtual std::int64_t repartition_interval() const { return 0; }
  /// Collective: every process's bytes, concatenated in rank order; `counts` receives each
  /// process's byte count.
  virtual std::vector<char> all_gather(const std::vector<char>& mine,
                                       std::vector<std::size_t>& counts) = 0;
};

/// Per-step figures of the distributed pair work, for the scaling measurements (this process).
struct DistributionStats {
  std::int64_t steps = 0;           ///< distributed steps taken (-)
  std::int64_t partitions = 0;      ///< partitions computed (the first one and rebalances) (-)
  std::int64_t owned_pairs = 0;     ///< candidate pairs this process evaluated, summed over steps
  std::int64_t ghost_blocks = 0;    ///< other processes' blocks in this process's pairs, summed
  std::int64_t bytes_sent = 0;      ///< bytes this process contributed to the exchanges (B)
  std::int64_t bytes_received = 0;  ///< bytes it received from the other processes (B)
  double pair_seconds = 0.0;        ///< time in its own pair work (s)
  double exchange_seconds = 0.0;    ///< time in the exchanges, waiting included (s)
  double last_imbalance = 1.0;      ///< slowest process's pair time over the mean, last step (-)
};

}  // namespace blockdem
