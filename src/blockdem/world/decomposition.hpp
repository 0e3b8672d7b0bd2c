// A world spread over processes (WorldSettings::distribution): which process owns each block, the
// blocks exact on this process, the parts of the step that exchange and reduce, the replica
// refresh and the merges to process 0. The step (world/step.cpp) calls its parts; a one-process
// world keeps it empty and never calls them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "blockdem/numerics/exact_sum.hpp"
#include "blockdem/world/contact.hpp"
#include "blockdem/world/distribution.hpp"
#include "blockdem/world/energy_budget.hpp"
#include "blockdem/world/step_scratch.hpp"

namespace blockdem {

class World;

/// The distributed bookkeeping of one world (every member is per process). Each process owns the
/// blocks of its subdomain (recursive coordinate bisection) and the pairs the ownership rule
/// gives it; it finds the pairs of its own blocks, evaluates its own pairs, sends each pair slot
/// to the owner of the pair's other block, sums the loads on its own blocks in the serial (a, b)
/// order, integrates them, and sends their new states to the processes that hold them as ghosts.
/// Global quantities are reduced exactly (minima, integer sums, exact accumulators of doubles).
/// Every exact block and slot is bit for bit what one process computes; synchronize() gathers
/// the whole world when a caller reads it. A new partition moves only the blocks that change
/// owner, point to point, with their slots (migrate_blocks). The world it serves is passed to
/// each call: a copied world copies this with it.
class Decomposition {
 public:
  // The step's parts (world/decomposition_step.cpp), in the order the step calls them.
  /// Before the step: the partition (the first, or after blocks changed), the resting blocks of
  /// a whole world, and the blocks exact on this process (s.held).
  void begin_step(World& world, StepScratch& s);
  /// The slots this process evaluates (the ownership rule), and the ghost sends they ask for.
  void select_own_pairs(World& world, StepScratch& s);
  /// After the own pairs' pass: every process agrees on a failure, each evaluated slot goes to
  /// the owner of its other block, and the received ones join this process's states.
  void exchange_evaluated_slots(World& world, StepScratch& s, const std::exception_ptr& error);
  /// This process's terms of the step's energy budget, summed over the processes (exact: as
  /// integers, the accumulators' limbs), so every process adds the step of one process.
  EnergyStepSums reduce_energy(World& world, StepScratch& s, const EnergyStepSums& mine);
  /// After integration: the ghosts for the next step, then the global checks and counts as exact
  /// reductions. Whether a process found a diverged block or a too-deep overlap.
  bool reduce_step_checks(World& world, StepScratch& s);
  /// At the step's end: a rebalance when the measured work is uneven, and the refresh.
  void end_step(World& world, StepScratch& s);

  /// A block whose pairs this process finds and keeps: its own, not resting.
  bool keeps_pairs_of(int i) const {
    return own_[static_cast<std::size_t>(i)] != 0 && resting_[static_cast<std::size_t>(i)] == 0;
  }
  /// The blocks this process integrates (its own), in index order, and per block whether it is.
  const std::vector<int>& own_list() const { return own_list_; }
  const std::vector<char>& own() const { return own_; }
  /// The blocks whose loads scatter_loads sums here (own and resting): listed, and per block.
  const std::vector<int>& kept_list() const { return kept_list_; }
  const std::vector<char>& keeps_loads() const { return keeps_loads_; }

  // The world's collective operations (World's public ones of the same names forward here).
  void synchronize(World& world);
  void save_state_to_root(World& world, const std::function<void(std::string_view)>& emit);
  std::vector<const Contact*> counted_contacts(const World& world) const;
  bool counts_contact(const World& world, const Contact& c) const;
  void reduce_partials(const World& world, std::span<ExactSum> sums, std::span<double> maxima,
                       std::span<std::int64_t> counts) const;
  std::vector<int> gather_indices(const World& world, const std::vector<int>& mine) const;
  void merge_to_root(const World& world, std::size_t count,
                     const std::function<std::uint64_t(std::size_t)>& key,
                     const std::function<void(std::size_t, std::string&)>& record,
                     const std::function<void(std::string_view)>& emit) const;
  std::vector<std::pair<int, Eigen::Vector3d>> resting_contact_forces(const World& world) const;
  /// The divergence checkpoint of a distributed step, its part (gathered by the next
  /// synchronize()).
  void save_checkpoint_part(World& world);

  /// Throws std::logic_error naming `what` unless the world is whole here.
  void require_replica(const char* what) const;
  const std::vector<int>& block_owners() const { return owner_; }
  const DistributionStats& stats() const { return dist_stats_; }
  bool replica_complete() const { return replica_complete_; }
  bool deferred_replica() const { return deferred_replica_; }
  void set_deferred_replica(bool on) { deferred_replica_ = on; }
  bool counts_block(std::size_t i) const { return replica_complete_ || own_[i] != 0; }
  /// a N + b of the first too-deep contact any process found (infinite: none).
  double overlap_key() const { return overlap_key_; }
  /// After the world was reset or loaded whole on every process: nothing to gather, the
  /// partition to be computed again at the next step.
  void forget_partition() {
    replica_complete_ = true;
    owner_.clear();
  }
  /// After a reset to the checkpoint: whole, with no overlap found.
  void reset_whole() {
    replica_complete_ = true;
    overlap_key_ = std::numeric_limits<double>::infinity();
  }

 private:
  void partition_blocks(World& world);
  /// Collective, on a distributed world that is not whole (deferred_replica_), at the end of a
  /// step: the partition partition_blocks() would compute, from each block's centroid and pair
  /// count sent by its owner, and each block that changes owner sent point to point to its new
  /// owner with the slots the new owner lacks; then one ghost exchange for the new subdomains.
  /// Makes the world whole and partitions (as partition_blocks) when the resting blocks would
  /// change.
  void migrate_blocks(World& world);
  // migrate_blocks's parts (world/decomposition_migrate.cpp): the new owners from each block's
  // centroid and pair count gathered from its owner (empty when a block came to rest or left
  // it), each moving block and the slots its new owner lacks as messages, the received ones
  // into place, and the slots as a step leaves them.
  struct Arrivals;
  std::vector<int> migration_owners(World& world, std::int64_t& sent, std::int64_t& received);
  std::vector<std::vector<char>> migration_messages(World& world, const std::vector<int>& owners,
                                                    std::int64_t& sent);
  Arrivals receive_migrated(World& world, const std::vector<std::vector<char>>& from,
                            const std::vector<int>& owners, std::int64_t& received);
  void keep_migrated_slots(World& world, Arrivals& in);
  /// A block's whole step state (pose, velocities, loads, stiffness sums, energy record, world
  /// planes and box) as bytes, and its reading (the state set on block `i` of the record; the
  /// offset past it returned), for a refresh or a migration.
  void put_block_state(const World& world, std::vector<char>& out, std::size_t i) const;
  std::size_t take_block_state(World& world, const std::vector<char>& in, std::size_t at,
                               std::size_t end, bool apply, std::size_t& i);
  int pair_owner(const World& world, int a, int b) const;
  void exchange_ghosts(World& world);
  /// After a distributed step that leaves the world not whole: gives back the room the pair
  /// stores kept from a whole world (a refresh, a restart, a rebalance), which this process
  /// holds only a part of. Changes no value.
  void release_spare_room(World& world);
  void mark_resting(World& world);
  /// Lists the blocks by own_ and resting_ (own_list_, moving_list_, kept_list_, keeps_loads_),
  /// after either changed.
  void list_own_blocks(World& world);
  void sum_resting_loads(World& world);
  void gather_checkpoint(World& world);  ///< collective: the parts into the whole checkpoint
  /// gather_checkpoint's parts: this process's part as bytes, and the resting blocks' energy
  /// records summed from the gathered contact terms (sorted here) as sum_resting_loads sums them.
  std::vector<char> checkpoint_part(World& world);
  void sum_checkpoint_resting(World& world, std::vector<std::array<double, 12>>& terms,
                              std::size_t resting_count);

  // save_state_to_root's sections (world/decomposition_replica.cpp).
  struct RootStream;
  /// The resting blocks' loads and stiffness sums, kRest values per resting block (at[i]: its
  /// place, or the block count for a block that is not resting), as sum_resting_loads sums them
  /// on a whole world, on every process.
  struct RestingTerms {
    std::vector<std::size_t> at;
    std::vector<double> values;
  };
  static constexpr std::size_t kRest = 11;  ///< force, torque, contact force, the two stiffnesses
  RestingTerms resting_terms(World& world);
  void blocks_to_root(World& world, RootStream& out, const RestingTerms& rest,
                      const std::vector<std::size_t>& mine);
  void slots_to_root(World& world, RootStream& out);
  void energy_to_root(World& world, RootStream& out, const RestingTerms& rest,
                      const std::vector<std::size_t>& mine);

  // Block owners, when they were last computed.
  std::vector<int> owner_;
  std::int64_t partition_step_ = -1;
  mutable DistributionStats dist_stats_;  ///< mutable: const reductions count their bytes
  bool replica_complete_ = true;          ///< every block and slot exact on this process
  bool deferred_replica_ = false;
  std::vector<char> own_;    ///< per block: owned by this process
  std::vector<char> local_;  ///< per block: exact here (owned, or a ghost received this step)
  /// Per block: fixed and at rest, marked on a whole world (mark_resting). Its state is the same
  /// on every process; its pairs and slots stay with the other blocks' owners, and its loads are
  /// summed only when the world is made whole (sum_resting_loads).
  std::vector<char> resting_;
  // Lists kept from the partition and mark_resting (list_own_blocks), in index order: the own
  // blocks; those of them not resting (what the ghost exchange sends); the blocks exact here
  // in every step (own or resting); and per block, whether its loads are summed here (the same).
  std::vector<int> own_list_, moving_list_, kept_list_;
  std::vector<char> keeps_loads_;
  /// The ghosts received by the last ghost exchange, in index order; valid when ghosts_listed_
  /// (local_ is then kept_list_ and these), not after local_ was set whole.
  std::vector<int> ghosts_;
  bool ghosts_listed_ = false;
  /// The ghost exchange's buffers, kept between steps: the moving own blocks' boxes at their new
  /// poses (per moving_list_ entry), the (own block, process) sends, and those that the step's
  /// slots ask for (an own block in a pair with another process's block), listed by the step.
  std::vector<Eigen::Vector3d> next_min_, next_max_;
  std::vector<std::pair<std::int64_t, int>> ghost_sends_, pair_sends_;
  double overlap_key_ =
      std::numeric_limits<double>::infinity();  ///< a N + b of the first too-deep contact
};

}  // namespace blockdem
