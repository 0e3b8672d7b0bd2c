// The per-pair work of a step spread over processes (settings().distribution): every process
// holds the whole world, evaluates the candidate pairs it owns, and receives the others' slots
// byte for byte, so that every process ends the step with the same state as a single process.
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "blockdem/world/world.hpp"

namespace blockdem {
namespace {

/// A process's part of an exchange starts with its measured pair time and its slot count.
struct ExchangeHeader {
  double seconds = 0.0;      ///< time in this step's own pair work (s)
  std::uint64_t slots = 0;   ///< number of slots that follow (-)
  std::uint64_t failed = 0;  ///< 1: a pair of this process threw (its slots are not sent)
};

/// Rebalance when the slowest process's pair work exceeds the mean by this factor (-)...
constexpr double kImbalanceThreshold = 1.25;
/// ... and at least this many steps have passed since the last partition (-).
constexpr std::int64_t kMinStepsBetweenPartitions = 100;
/// ... and the slowest process loses more than this per step against the mean (s): below it the
/// measured times are mostly noise, and an imbalance costs nothing worth a partition.
constexpr double kMinImbalanceSeconds = 1e-3;
/// ... and the processes' pair counts are uneven by this factor too (-): the bisection balances
/// pair counts, so only then can a new partition help (and counts carry no timing noise).
constexpr double kPairCountThreshold = 1.1;

}  // namespace

void World::partition_blocks() {
  // Weight: one for the block plus one per candidate pair it is in (the narrow phase's work).
  std::vector<Eigen::Vector3d> points(blocks_.size());
  std::vector<double> weights(blocks_.size(), 1.0);
  for (std::size_t i = 0; i < blocks_.size(); ++i) points[i] = blocks_[i].position;
  for (const auto& s : slots_) {
    weights[static_cast<std::size_t>(s.contact.a)] += 1.0;
    weights[static_cast<std::size_t>(s.contact.b)] += 1.0;
  }
  owner_ = settings_.distribution->partition(points, weights);
  if (owner_.size() != blocks_.size())
    throw std::logic_error("partition: one owner per block expected");
  partition_step_ = step_count_;
  ++dist_stats_.partitions;
}

void World::evaluate_pairs_distributed(double dt, int threads) {
  // A slot travels as raw bytes: Contact and PairSlot hold fixed-size data only (no pointers,
  // no heap storage), and every process runs the same program.
  static_assert(std::is_trivially_destructible_v<PairSlot>, "PairSlot must be plain data");
  PairDistribution& dist = *settings_.distribution;
  const int rank = dist.rank();
  if (owner_.size() != blocks_.size()) partition_blocks();

  // One owner per pair, by a rule on the blocks' global indices: the owner of the block that
  // can move when only one can; otherwise of a when a + b is odd, of b when even (so that pairs
  // across a subdomain boundary split about evenly between the two sides).
  auto pair_owner = [&](const Contact& c) {
    const bool da = blocks_[c.a].is_dynamic(), db = blocks_[c.b].is_dynamic();
    if (da != db) return owner_[da ? c.a : c.b];
    return owner_[((c.a + c.b) & 1) != 0 ? c.a : c.b];
  };
  std::vector<int> slot_owner(slots_.size());
  std::vector<std::int64_t> mine;
  std::vector<char> ghost(blocks_.size(), 0);
  for (std::size_t k = 0; k < slots_.size(); ++k) {
    slot_owner[k] = pair_owner(slots_[k].contact);
    if (slot_owner[k] != rank) continue;
    mine.push_back(static_cast<std::int64_t>(k));
    const Contact& c = slots_[k].contact;
    if (owner_[c.a] != rank) ghost[c.a] = 1;
    if (owner_[c.b] != rank) ghost[c.b] = 1;
  }
  for (char g : ghost) dist_stats_.ghost_blocks += g;

  // This process's pairs (in parallel over its threads; each writes only its own slot).
  const auto t0 = std::chrono::steady_clock::now();
  const std::int64_t n = static_cast<std::int64_t>(mine.size());
  std::int64_t failed = n;
  std::exception_ptr error;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) if (threads > 1 && n > 64)
  for (std::int64_t i = 0; i < n; ++i) {
    try {
      evaluate_pair(slots_[static_cast<std::size_t>(mine[static_cast<std::size_t>(i)])], dt, true);
    } catch (...) {
#pragma omp critical(blockdem_pair_error)
      if (i < failed) {
        failed = i;
        error = std::current_exception();
      }
    }
  }
  // A pair that throws: the exchange still runs, and every process then stops alike.
  if (error) mine.clear();
  const auto t1 = std::chrono::steady_clock::now();

  ExchangeHeader header;
  header.seconds = std::chrono::duration<double>(t1 - t0).count();
  header.slots = static_cast<std::uint64_t>(mine.size());
  header.failed = error ? 1 : 0;
  std::vector<char> out(sizeof(ExchangeHeader) + mine.size() * sizeof(PairSlot));
  std::memcpy(out.data(), &header, sizeof header);
  for (std::size_t i = 0; i < mine.size(); ++i) {
    std::memcpy(out.data() + sizeof header + i * sizeof(PairSlot),
                static_cast<const void*>(&slots_[static_cast<std::size_t>(mine[i])]),
                sizeof(PairSlot));
  }
  std::vector<std::size_t> counts;
  const std::vector<char> all = dist.all_gather(out, counts);
  const auto t2 = std::chrono::steady_clock::now();

  if (error) std::rethrow_exception(error);
  // Every other process's slots, in rank order; each process's slots come in slot order.
  std::vector<std::size_t> begin(counts.size() + 1, 0);
  for (std::size_t r = 0; r < counts.size(); ++r) begin[r + 1] = begin[r] + counts[r];
  std::vector<std::size_t> next(counts.size());
  double slowest = 0.0, total = 0.0, most_pairs = 0.0, total_pairs = 0.0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    ExchangeHeader h;
    std::memcpy(&h, all.data() + begin[r], sizeof h);
    if (h.failed != 0)
      throw std::runtime_error("contact evaluation failed on process " + std::to_string(r));
    if (sizeof h + h.slots * sizeof(PairSlot) != counts[r])
      throw std::logic_error("pair exchange: a process sent a malformed part");
    slowest = std::max(slowest, h.seconds);
    total += h.seconds;
    most_pairs = std::max(most_pairs, static_cast<double>(h.slots));
    total_pairs += static_cast<double>(h.slots);
    next[r] = begin[r] + sizeof h;
  }
  for (std::size_t k = 0; k < slots_.size(); ++k) {
    const auto r = static_cast<std::size_t>(slot_owner[k]);
    if (next[r] + sizeof(PairSlot) > begin[r + 1])
      throw std::logic_error("pair exchange: a process sent fewer pairs than it owns");
    if (slot_owner[k] != rank)
      std::memcpy(static_cast<void*>(&slots_[k]), all.data() + next[r], sizeof(PairSlot));
    next[r] += sizeof(PairSlot);
  }

  dist_stats_.steps += 1;
  dist_stats_.owned_pairs += n;
  dist_stats_.bytes_sent += static_cast<std::int64_t>(out.size());
  dist_stats_.bytes_received += static_cast<std::int64_t>(all.size() - out.size());
  dist_stats_.pair_seconds += header.seconds;
  dist_stats_.exchange_seconds += std::chrono::duration<double>(t2 - t1).count();
  // Rebalancing: every process sees the same measured times, so all decide alike. The answers do
  // not depend on the partition, only the speed does.
  const double mean = total / static_cast<double>(counts.size());
  dist_stats_.last_imbalance = mean > 0.0 ? slowest / mean : 1.0;
  const std::int64_t since = step_count_ + 1 - partition_step_;
  const std::int64_t every = dist.repartition_interval();
  const double mean_pairs = total_pairs / static_cast<double>(counts.size());
  const bool uneven_pairs = most_pairs > kPairCountThreshold * mean_pairs;
  if ((dist_stats_.last_imbalance > kImbalanceThreshold && slowest - mean > kMinImbalanceSeconds &&
       uneven_pairs && since >= kMinStepsBetweenPartitions) ||
      (every > 0 && since >= every))
    partition_blocks();
}

}  // namespace blockdem
