// The hook through which a world spreads its step over processes (MPI ranks): which process owns
// which block, point-to-point exchanges with neighbours, reductions and an all-gather of bytes.
// Implemented in parallel/ (floor 4).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace blockdem {

/// What the world needs from a group of processes that run the same scenario in lockstep. Every
/// process owns the blocks of its subdomain and the contacts the ownership rule gives it; it
/// steps those, with ghost copies of its neighbours' blocks, and the whole world is gathered to
/// every process only when asked (World::synchronize).
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

  // The operations below have implementations built on all_gather (correct, but every process
  // then receives everything); parallel/mpi_run overrides them with point-to-point messages and
  // MPI reductions, whose volume follows the subdomains' surfaces.

  /// Collective: `to[r]` goes to process r (an empty part sends nothing; to[rank()] is ignored);
  /// returns what each process sent to this one, indexed by sender.
  virtual std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& to);
  /// Collective: the element-wise minimum over every process (exact: independent of order).
  virtual std::vector<double> min(const std::vector<double>& mine);
  /// Collective: the element-wise sum over every process (exact: integers).
  virtual std::vector<std::int64_t> sum(const std::vector<std::int64_t>& mine);
  /// Collective: every process's bytes, concatenated in rank order, on process 0 only (empty on
  /// the others); `counts` receives each process's byte count on process 0.
  virtual std::vector<char> gather(const std::vector<char>& mine, std::vector<std::size_t>& counts);
  /// Collective: process 0's bytes replace `bytes` on every process.
  virtual void broadcast(std::vector<char>& bytes);
};

/// Per-step figures of the distributed pair work, for the scaling measurements (this process).
struct DistributionStats {
  std::int64_t steps = 0;         ///< distributed steps taken (-)
  std::int64_t partitions = 0;    ///< partitions computed (the first one and rebalances) (-)
  std::int64_t owned_pairs = 0;   ///< candidate pairs this process evaluated, summed over steps
  std::int64_t ghost_blocks = 0;  ///< other processes' blocks in this process's pairs, summed
  /// Bytes this process sent to its neighbours every step: pair slots to the other block's owner,
  /// its blocks' states to the processes that hold them as ghosts, and its part of the fixed-order
  /// sums (B).
  std::int64_t bytes_sent = 0;
  std::int64_t bytes_received = 0;  ///< bytes it received in those exchanges (B)
  /// Replica refreshes (every block and pair slot to every process: whenever the caller reads
  /// the whole world, and partitions and divergence checkpoints when it does not defer the
  /// refresh) and their bytes (B).
  std::int64_t replica_refreshes = 0;
  std::int64_t replica_bytes_sent = 0;
  std::int64_t replica_bytes_received = 0;
  /// Rebalances that migrated blocks point to point (World::migrate_blocks) instead of making the
  /// world whole: the rebalances, the blocks and pair slots this process sent to new owners, and
  /// the bytes it sent and received in them (B): the partition's input (a block's centroid and
  /// pair count from its owner, to every process), the migrated blocks and slots, and the ghost
  /// exchange for the new subdomains.
  std::int64_t migrations = 0;
  std::int64_t migrated_blocks = 0;
  std::int64_t migrated_slots = 0;
  std::int64_t migration_bytes_sent = 0;
  std::int64_t migration_bytes_received = 0;
  /// Outputs merged to process 0 instead of read from a whole world (World::merge_to_root):
  /// the merges, and the bytes this process sent and (process 0) received in them (B).
  std::int64_t output_merges = 0;
  std::int64_t output_bytes_sent = 0;
  std::int64_t output_bytes_received = 0;
  /// Divergence checkpoints kept in parts and gathered (World::gather_checkpoint, at the next
  /// refresh): the gathers, and the bytes this process sent and received in them (B).
  std::int64_t checkpoint_gathers = 0;
  std::int64_t checkpoint_bytes_sent = 0;
  std::int64_t checkpoint_bytes_received = 0;
  double pair_seconds = 0.0;       ///< time in its own pair work (s)
  double exchange_seconds = 0.0;   ///< time in the per-step exchanges, waiting included (s)
  double replica_seconds = 0.0;    ///< time in the replica refreshes, waiting included (s)
  double migration_seconds = 0.0;  ///< time in the migrations, waiting included (s)
  double last_imbalance = 1.0;     ///< slowest process's pair time over the mean, last step (-)
};

}  // namespace blockdem
