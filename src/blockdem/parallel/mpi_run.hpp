// An MPI run: the session (MPI started only when a launcher such as mpirun or srun started this
// process), the pair distribution over its ranks, and the collective checks a run needs.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "blockdem/world/distribution.hpp"

namespace blockdem {

/// Per-step figures of a process's share of a distributed run (means over its steps), for
/// summary.json: pairs, ghost blocks, bytes sent and received, pair and exchange times.
nlohmann::json distribution_json(const DistributionStats& stats);
/// Collective: distribution_json of every process, in rank order (an array).
nlohmann::json gather_distribution_json(PairDistribution& distribution,
                                        const DistributionStats& stats);

/// True when the program was built with MPI (BLOCKDEM_MPI).
bool mpi_built();

/// True when a process launcher (mpirun, mpiexec, srun) started this process, judged from the
/// environment variables Open MPI, MPICH/Hydra, PMIx and Slurm set.
bool launched_by_mpi_launcher();

/// Starts MPI when launched by a launcher (and built with MPI); ends it when destroyed. Without a
/// launcher the program runs as one process and MPI is never started.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  bool active() const { return active_; }  ///< MPI was started
  int rank() const { return rank_; }
  int size() const { return size_; }

  /// Collective: whether every rank succeeded. When some failed, `message` becomes the message
  /// of the lowest failing rank, on every rank.
  bool all_ok(bool ok, std::string& message) const;
  /// Ends every rank of the run at once with this exit code (MPI_Abort).
  [[noreturn]] void abort(int code) const;
  /// Collective: the element-wise maximum of `values` over every rank (unchanged for one
  /// process). Cheap enough for every step: one MPI_Allreduce of a few integers.
  void max_over_ranks(std::vector<int>& values) const;
  /// Collective: `bytes` of rank `root` on every rank (sent in pieces of at most 1 GiB).
  void broadcast(std::string& bytes, int root) const;
  /// Collective: returns when every rank has called it.
  void barrier() const;

  /// The pair distribution over this session's ranks (null when size() == 1).
  std::shared_ptr<PairDistribution> distribution() const;

 private:
  bool active_ = false;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace blockdem
