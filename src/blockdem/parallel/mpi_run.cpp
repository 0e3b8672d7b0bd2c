// The MPI session and the pair distribution over MPI_COMM_WORLD. Without BLOCKDEM_HAVE_MPI the
// session is always a single process.
#include "blockdem/parallel/mpi_run.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "blockdem/parallel/rcb.hpp"

#ifdef BLOCKDEM_HAVE_MPI
#include <mpi.h>
#endif

namespace blockdem {

bool mpi_built() {
#ifdef BLOCKDEM_HAVE_MPI
  return true;
#else
  return false;
#endif
}

nlohmann::json distribution_json(const DistributionStats& s) {
  const double steps = s.steps > 0 ? static_cast<double>(s.steps) : 1.0;
  return {
      {"steps", s.steps},
      {"partitions", s.partitions},
      {"pairs_per_step", static_cast<double>(s.owned_pairs) / steps},
      {"ghost_blocks_per_step", static_cast<double>(s.ghost_blocks) / steps},
      {"bytes_sent_per_step", static_cast<double>(s.bytes_sent) / steps},
      {"bytes_received_per_step", static_cast<double>(s.bytes_received) / steps},
      {"replica_refreshes", s.replica_refreshes},
      {"replica_bytes_sent_per_step", static_cast<double>(s.replica_bytes_sent) / steps},
      {"replica_bytes_received_per_step", static_cast<double>(s.replica_bytes_received) / steps},
      {"migrations", s.migrations},
      {"migrated_blocks", s.migrated_blocks},
      {"migrated_slots", s.migrated_slots},
      {"migration_bytes_sent", s.migration_bytes_sent},
      {"migration_bytes_received", s.migration_bytes_received},
      {"migration_seconds", s.migration_seconds},
      {"output_merges", s.output_merges},
      {"output_bytes_sent", s.output_bytes_sent},
      {"output_bytes_received", s.output_bytes_received},
      {"checkpoint_gathers", s.checkpoint_gathers},
      {"checkpoint_bytes_sent", s.checkpoint_bytes_sent},
      {"checkpoint_bytes_received", s.checkpoint_bytes_received},
      {"pair_seconds_per_step", s.pair_seconds / steps},
      {"exchange_seconds_per_step", s.exchange_seconds / steps},
      {"replica_seconds_per_step", s.replica_seconds / steps},
      {"last_imbalance", s.last_imbalance}};
}

nlohmann::json gather_distribution_json(PairDistribution& distribution,
                                        const DistributionStats& stats) {
  static_assert(std::is_trivially_copyable_v<DistributionStats>);
  std::vector<char> mine(sizeof stats);
  std::memcpy(mine.data(), &stats, sizeof stats);
  std::vector<std::size_t> counts;
  const std::vector<char> all = distribution.all_gather(mine, counts);
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t r = 0; r * sizeof stats < all.size(); ++r) {
    DistributionStats s;
    std::memcpy(&s, all.data() + r * sizeof stats, sizeof s);
    out.push_back(distribution_json(s));
  }
  return out;
}

bool launched_by_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                           "MPI_LOCALNRANKS", "SLURM_PMIX_MAPPING_SERV"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#ifdef BLOCKDEM_HAVE_MPI
namespace {

class MpiPairDistribution final : public PairDistribution {
 public:
  MpiPairDistribution(int rank, int size) : rank_(rank), size_(size) {
    // A fixed repartition interval, for tests and for studying the cost of migration.
    if (const char* every = std::getenv("BLOCKDEM_MPI_REBALANCE_STEPS"))
      interval_ = std::max<std::int64_t>(0, std::atoll(every));
  }
  std::int64_t repartition_interval() const override { return interval_; }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::vector<int> partition(std::span<const Eigen::Vector3d> points,
                             std::span<const double> weights) const override {
    return recursive_coordinate_bisection(points, weights, size_);
  }
  std::vector<char> all_gather(const std::vector<char>& mine,
                               std::vector<std::size_t>& counts) override {
    if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::runtime_error("pair exchange: more than 2 GB from one process");
    const int count = static_cast<int>(mine.size());
    std::vector<int> all_counts(static_cast<std::size_t>(size_));
    MPI_Allgather(&count, 1, MPI_INT, all_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::vector<int> displs(static_cast<std::size_t>(size_), 0);
    long long total = 0;
    counts.assign(static_cast<std::size_t>(size_), 0);
    for (int r = 0; r < size_; ++r) {
      if (total > std::numeric_limits<int>::max())
        throw std::runtime_error("pair exchange: more than 2 GB in one step");
      displs[static_cast<std::size_t>(r)] = static_cast<int>(total);
      counts[static_cast<std::size_t>(r)] =
          static_cast<std::size_t>(all_counts[static_cast<std::size_t>(r)]);
      total += all_counts[static_cast<std::size_t>(r)];
    }
    std::vector<char> all(static_cast<std::size_t>(total));
    MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), all_counts.data(), displs.data(),
                   MPI_BYTE, MPI_COMM_WORLD);
    return all;
  }

  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& to) override {
    // Byte counts to every process (one integer each), then a message only where there are
    // bytes: point to point, received into per-sender buffers, so the order of arrival does not
    // matter.
    const auto k = static_cast<std::size_t>(size_);
    if (to.size() != k) throw std::logic_error("exchange: one part per process expected");
    std::vector<int> send_counts(k, 0), recv_counts(k, 0);
    for (std::size_t r = 0; r < k; ++r) {
      if (static_cast<int>(r) == rank_) continue;
      if (to[r].size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw std::runtime_error("exchange: more than 2 GB to one process");
      send_counts[r] = static_cast<int>(to[r].size());
    }
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::vector<std::vector<char>> from(k);
    std::vector<MPI_Request> requests;
    requests.reserve(2 * k);
    for (std::size_t r = 0; r < k; ++r) {
      if (recv_counts[r] == 0) continue;
      from[r].resize(static_cast<std::size_t>(recv_counts[r]));
      requests.emplace_back();
      MPI_Irecv(from[r].data(), recv_counts[r], MPI_BYTE, static_cast<int>(r), kExchangeTag,
                MPI_COMM_WORLD, &requests.back());
    }
    for (std::size_t r = 0; r < k; ++r) {
      if (send_counts[r] == 0) continue;
      requests.emplace_back();
      MPI_Isend(to[r].data(), send_counts[r], MPI_BYTE, static_cast<int>(r), kExchangeTag,
                MPI_COMM_WORLD, &requests.back());
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return from;
  }
  std::vector<double> min(const std::vector<double>& mine) override {
    std::vector<double> out(mine.size());
    MPI_Allreduce(mine.data(), out.data(), static_cast<int>(mine.size()), MPI_DOUBLE, MPI_MIN,
                  MPI_COMM_WORLD);
    return out;
  }
  std::vector<std::int64_t> sum(const std::vector<std::int64_t>& mine) override {
    static_assert(sizeof(long long) == sizeof(std::int64_t));
    std::vector<std::int64_t> out(mine.size());
    MPI_Allreduce(mine.data(), out.data(), static_cast<int>(mine.size()), MPI_LONG_LONG, MPI_SUM,
                  MPI_COMM_WORLD);
    return out;
  }
  std::vector<char> gather(const std::vector<char>& mine,
                           std::vector<std::size_t>& counts) override {
    if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::runtime_error("gather: more than 2 GB from one process");
    const int count = static_cast<int>(mine.size());
    std::vector<int> all_counts(static_cast<std::size_t>(size_), 0);
    MPI_Gather(&count, 1, MPI_INT, all_counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<int> displs(static_cast<std::size_t>(size_), 0);
    long long total = 0;
    counts.clear();
    if (rank_ == 0) {
      for (int r = 0; r < size_; ++r) {
        if (total > std::numeric_limits<int>::max())
          throw std::runtime_error("gather: more than 2 GB in one step");
        displs[static_cast<std::size_t>(r)] = static_cast<int>(total);
        counts.push_back(static_cast<std::size_t>(all_counts[static_cast<std::size_t>(r)]));
        total += all_counts[static_cast<std::size_t>(r)];
      }
    }
    std::vector<char> all(static_cast<std::size_t>(total));
    MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), all_counts.data(), displs.data(),
                MPI_BYTE, 0, MPI_COMM_WORLD);
    return all;
  }
  void broadcast(std::vector<char>& bytes) override {
    unsigned long long n = bytes.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    if (n > static_cast<unsigned long long>(std::numeric_limits<int>::max()))
      throw std::runtime_error("broadcast: more than 2 GB");
    bytes.resize(static_cast<std::size_t>(n));
    MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, 0, MPI_COMM_WORLD);
  }

 private:
  static constexpr int kExchangeTag = 17;
  int rank_;
  int size_;
  std::int64_t interval_ = 0;
};

}  // namespace

MpiSession::MpiSession() {
  if (!launched_by_mpi_launcher()) return;
  int provided = 0;
  // Only the main thread calls MPI; OpenMP threads work between the calls.
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
}

bool MpiSession::all_ok(bool ok, std::string& message) const {
  if (!active_ || size_ == 1) return ok;
  // The lowest failing rank (size_ when none) sends its message to all.
  int failing = ok ? size_ : rank_;
  int first = size_;
  MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == size_) return true;
  int length = rank_ == first ? static_cast<int>(message.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  return false;
}

void MpiSession::abort(int code) const {
  if (active_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

void MpiSession::max_over_ranks(std::vector<int>& values) const {
  if (!active_ || size_ == 1 || values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_INT, MPI_MAX,
                MPI_COMM_WORLD);
}

void MpiSession::broadcast(std::string& bytes, int root) const {
  if (!active_ || size_ == 1) return;
  long long length = static_cast<long long>(bytes.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, root, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(length));
  constexpr long long kPiece = 1LL << 30;
  for (long long at = 0; at < length; at += kPiece) {
    const int count = static_cast<int>(std::min(kPiece, length - at));
    MPI_Bcast(bytes.data() + at, count, MPI_CHAR, root, MPI_COMM_WORLD);
  }
}

void MpiSession::barrier() const {
  if (active_ && size_ > 1) MPI_Barrier(MPI_COMM_WORLD);
}

std::shared_ptr<PairDistribution> MpiSession::distribution() const {
  if (!active_ || size_ == 1) return nullptr;
  return std::make_shared<MpiPairDistribution>(rank_, size_);
}

#else

MpiSession::MpiSession() = default;
MpiSession::~MpiSession() = default;
bool MpiSession::all_ok(bool ok, std::string&) const {
  return ok;
}
void MpiSession::abort(int code) const {
  std::exit(code);
}
void MpiSession::max_over_ranks(std::vector<int>&) const {}
void MpiSession::broadcast(std::string&, int) const {}
void MpiSession::barrier() const {}
std::shared_ptr<PairDistribution> MpiSession::distribution() const {
  return nullptr;
}

#endif

}  // namespace blockdem
