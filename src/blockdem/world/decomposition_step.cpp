// The distributed step's own parts (World::step calls them between its passes): the exact blocks
// of this process, the ghost exchange, the own pairs and the exchange of evaluated slots, the
// exact reductions of the energy budget and the checks, and the rebalance at the step's end.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "blockdem/world/decomposition.hpp"
#include "blockdem/world/decomposition_wire.hpp"
#include "blockdem/world/pair_owner.hpp"
#include "blockdem/world/world.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace blockdem {

using namespace decomposition_wire;

void Decomposition::exchange_ghosts(World& world) {
  // After integration: each process's own blocks to every process whose subdomain box (the union
  // of its blocks' boxes) their box touches, and to the owners of their pairs' other blocks (an
  // open bond keeps a pair whose boxes have parted; listed by the step in pair_sends_). A
  // process then holds, exactly, every block whose box can touch one of its own: its next broad
  // phase and pair work need no other. The walks cover the moving own blocks and the received
  // ghosts only, in buffers kept between steps.
  PairDistribution& dist = *world.settings_.distribution;
  const int rank = dist.rank();
  const auto k = static_cast<std::size_t>(dist.size());
  const std::size_t n = world.blocks_.size();
  // The own blocks' boxes at their new poses (as the next step's geometry pass computes them;
  // the blocks keep this step's planes and boxes, as in one process). A process's subdomain is
  // published as the union of its movable blocks' boxes plus the box of each fixed block that is
  // not resting, so that a base plate under the whole model does not make the union the whole
  // model. A resting block is exact on every process: it is neither sent nor needs ghosts.
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(inf), hi = Eigen::Vector3d::Constant(-inf);
  const std::size_t moving = moving_list_.size();
  next_min_.assign(moving, lo);
  next_max_.assign(moving, hi);
  std::vector<char> box;
  for (std::size_t m = 0; m < moving; ++m) {
    const Block& b = world.blocks_[static_cast<std::size_t>(moving_list_[m])];
    const Eigen::Matrix3d rot = b.rotation();
    for (const auto& v : b.shape.vertices()) {
      const Eigen::Vector3d w = b.position + rot * v;
      next_min_[m] = next_min_[m].cwiseMin(w);
      next_max_[m] = next_max_[m].cwiseMax(w);
    }
    if (b.motion == Motion::fixed) {
      put3(box, next_min_[m]);
      put3(box, next_max_[m]);
    } else {
      lo = lo.cwiseMin(next_min_[m]);
      hi = hi.cwiseMax(next_max_[m]);
    }
  }
  put3(box, lo);
  put3(box, hi);
  std::vector<std::size_t> counts;
  const std::vector<char> boxes = dist.all_gather(box, counts);
  std::vector<std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>> subdomain(k);
  std::size_t begin = 0;
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t at = begin; at + 48 <= begin + counts[r]; at += 48)
      subdomain[r].emplace_back(get3(boxes, at), get3(boxes, at + 24));
    begin += counts[r];
  }
  // (own block, destination) pairs: by the boxes, then the other owners of its pairs; each
  // message lists its blocks in index order.
  std::vector<std::pair<std::int64_t, int>>& sends = ghost_sends_;
  sends.clear();
  for (std::size_t m = 0; m < moving; ++m) {
    for (std::size_t r = 0; r < k; ++r) {
      if (static_cast<int>(r) == rank) continue;
      for (const auto& [box_lo, box_hi] : subdomain[r]) {
        if (boxes_overlap(next_min_[m], next_max_[m], box_lo, box_hi)) {
          sends.emplace_back(static_cast<std::int64_t>(moving_list_[m]), static_cast<int>(r));
          break;
        }
      }
    }
  }
  sends.insert(sends.end(), pair_sends_.begin(), pair_sends_.end());
  std::sort(sends.begin(), sends.end());
  sends.erase(std::unique(sends.begin(), sends.end()), sends.end());
  std::vector<std::vector<char>> to(k);
  for (const auto& [i, r] : sends)
    put_ghost(to[static_cast<std::size_t>(r)], world.blocks_[static_cast<std::size_t>(i)]);
  const std::vector<std::vector<char>> from = dist.exchange(to);
  // The last step's ghosts are exact here no more (every block, after a refresh).
  if (ghosts_listed_) {
    for (const int g : ghosts_) local_[static_cast<std::size_t>(g)] = 0;
  } else {
    for (std::size_t i = 0; i < n; ++i) local_[i] = own_[i] != 0 || resting_[i] != 0 ? 1 : 0;
  }
  ghosts_.clear();
  for (std::size_t r = 0; r < k; ++r) {
    if (from[r].size() % kGhostBytes != 0)
      throw std::logic_error("ghost exchange: a process sent a malformed part");
    std::size_t at = 0;
    WireReader in(from[r], at, from[r].size(), "ghost exchange");
    LoadArchive ar(in);
    while (at < from[r].size()) {
      const auto i = static_cast<std::size_t>(in.pod<std::int64_t>());
      if (i >= n || owner_[i] != static_cast<int>(r))
        throw std::logic_error("ghost exchange: a block came from a process that does not own it");
      motion_record(ar, world.blocks_[i]);
      local_[i] = 1;
      ghosts_.push_back(static_cast<int>(i));
    }
    dist_stats_.bytes_received += static_cast<std::int64_t>(from[r].size());
  }
  // Each process's list is in index order, and the processes own disjoint blocks.
  std::sort(ghosts_.begin(), ghosts_.end());
  ghosts_listed_ = true;
  for (std::size_t r = 0; r < k; ++r)
    dist_stats_.bytes_sent += static_cast<std::int64_t>(to[r].size());
  dist_stats_.bytes_sent += static_cast<std::int64_t>(box.size());
  dist_stats_.bytes_received += static_cast<std::int64_t>(boxes.size() - box.size());
}

void Decomposition::begin_step(World& world, StepScratch& s) {
  world.drop_primed();  // the distributed step solves its own pairs
  const std::size_t n = world.blocks_.size();
  if (owner_.size() != n) {
    synchronize(world);
    partition_blocks(world);
  }
  if (replica_complete_) {
    local_.assign(n, 1);
    ghosts_listed_ = false;
    mark_resting(world);
  }
  // The exact blocks: the kept ones and the last exchange's ghosts (disjoint lists), or after a
  // refresh every block local_ marks.
  if (ghosts_listed_) {
    s.held.resize(kept_list_.size() + ghosts_.size());
    std::merge(kept_list_.begin(), kept_list_.end(), ghosts_.begin(), ghosts_.end(),
               s.held.begin());
  } else {
    s.held.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      if (local_[i] != 0) s.held.push_back(static_cast<int>(i));
  }
}

void Decomposition::select_own_pairs(World& world, StepScratch& s) {
  const int rank = world.settings_.distribution->rank();
  const auto owner_of = [&](const World::PairSlot& c) {
    return pair_owner_process(owner_, c.a, s.moves[static_cast<std::size_t>(c.a)] != 0, c.b,
                              s.moves[static_cast<std::size_t>(c.b)] != 0);
  };
  // The same walk lists the (own block, process) pairs that the ghost exchange sends for the
  // slots: an own block to the owner of its pair's other block (an open bond keeps a pair whose
  // boxes have parted), neither block resting.
  std::vector<int> ghost;  // the other processes' blocks in this process's pairs
  s.mine.clear();
  s.is_mine.assign(world.slots_.size(), 0);
  pair_sends_.clear();
  for (std::size_t k = 0; k < world.slots_.size(); ++k) {
    const World::PairSlot& c = world.slots_[k];
    const int ca = c.a, cb = c.b;
    if ((own_[ca] == 0 || own_[cb] == 0) && resting_[ca] == 0 && resting_[cb] == 0) {
      if (own_[ca] != 0 && owner_[cb] != rank) pair_sends_.emplace_back(ca, owner_[cb]);
      if (own_[cb] != 0 && owner_[ca] != rank) pair_sends_.emplace_back(cb, owner_[ca]);
    }
    if (owner_of(c) != rank) continue;
    s.mine.push_back(static_cast<std::int64_t>(k));
    s.is_mine[k] = 1;
    if (own_[ca] == 0) ghost.push_back(ca);
    if (own_[cb] == 0) ghost.push_back(cb);
  }
  std::sort(ghost.begin(), ghost.end());
  dist_stats_.ghost_blocks += std::unique(ghost.begin(), ghost.end()) - ghost.begin();
}

void Decomposition::exchange_evaluated_slots(World& world, StepScratch& s,
                                             const std::exception_ptr& error) {
  PairDistribution& dist = *world.settings_.distribution;
  const int rank = dist.rank();
  const auto k_ranks = static_cast<std::size_t>(dist.size());
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  // Every process's figures (pair time and count, failure): all decide alike on failures and
  // on rebalancing.
  StepHeader header;
  header.seconds = s.pair_seconds;
  header.slots = static_cast<std::uint64_t>(s.mine.size());
  // A refused value (std::invalid_argument of a law or the narrow phase) and its message.
  std::string refused;
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::invalid_argument& e) {
      refused = e.what();
    } catch (...) {
    }
  }
  header.failed = !error ? 0 : !refused.empty() ? 1 : 2;
  std::vector<char> head;
  put(head, header);
  std::vector<std::size_t> counts;
  auto tw = Clock::now();
  const std::vector<char> heads = dist.all_gather(head, counts);
  s.waiting += seconds_since(tw);
  for (std::size_t r = 0; r < k_ranks; ++r) {
    const auto h = get<StepHeader>(heads, r * sizeof(StepHeader));
    if (h.failed == 1) {
      // A value refused on process r (the first in process order): its message to every
      // process, the whole world on every process, and the one-process reset and StepFailure.
      world.settle_contacts();
      std::vector<std::size_t> sizes;
      const std::vector<char> texts =
          dist.all_gather(std::vector<char>(refused.begin(), refused.end()), sizes);
      std::size_t at = 0;
      for (std::size_t q = 0; q < r; ++q) at += sizes[q];
      const std::string why(texts.begin() + static_cast<std::ptrdiff_t>(at),
                            texts.begin() + static_cast<std::ptrdiff_t>(at + sizes[r]));
      synchronize(world);
      world.fail_step(why);
    }
    if (h.failed != 0) {
      world.settle_contacts();
      if (error) std::rethrow_exception(error);
      throw std::runtime_error("contact evaluation failed on process " + std::to_string(r));
    }
    s.slowest = std::max(s.slowest, h.seconds);
    s.total += h.seconds;
    s.most_pairs = std::max(s.most_pairs, static_cast<double>(h.slots));
    s.total_pairs += static_cast<double>(h.slots);
  }

  // Each evaluated slot to the owner of the pair's other block, byte for byte (not to a resting
  // block's owner: its loads wait for the whole world, sum_resting_loads).
  // A slot that formed a contact this step finds its state in its run's list.
  const auto state_of = [&](std::size_t k) -> const Contact* {
    const World::PairSlot& slot = world.slots_[k];
    if (!slot.active) return nullptr;
    if (!slot.pending) return &world.contact_of(slot);
    const std::vector<World::PendingContact>& list = world.pending_[k / world.pending_run_];
    const auto it = std::lower_bound(
        list.begin(), list.end(), k,
        [](const World::PendingContact& p, std::size_t at) { return p.slot < at; });
    if (it == list.end() || it->slot != k)
      throw std::logic_error("pair exchange: a new contact state is missing");
    return &it->contact;
  };
  std::vector<std::vector<char>> to(k_ranks);
  for (std::int64_t i : s.mine) {
    const World::PairSlot& slot = world.slots_[static_cast<std::size_t>(i)];
    for (int block : {slot.a, slot.b}) {
      const int r = owner_[static_cast<std::size_t>(block)];
      if (r == rank || resting_[static_cast<std::size_t>(block)] != 0) continue;
      put_slot(to[static_cast<std::size_t>(r)], slot, state_of(static_cast<std::size_t>(i)));
    }
  }
  tw = Clock::now();
  const std::vector<std::vector<char>> from = dist.exchange(to);
  s.waiting += seconds_since(tw);
  // The received slots replace this process's (none of its own pairs); their contact states
  // join the new ones in pending_, each run's list then put back in slot order.
  if (world.pending_.size() != (world.slots_.size() + world.pending_run_ - 1) / world.pending_run_)
    throw std::logic_error("pair exchange: the new contact states are not the slots'");
  std::vector<char> joined(world.pending_.size(), 0);
  for (std::size_t r = 0; r < k_ranks; ++r) {
    std::size_t at = 0;
    while (at < from[r].size()) {
      World::PairSlot received;
      Contact state;
      if (!get_slot(from[r], at, from[r].size(), received, state))
        throw std::logic_error("pair exchange: a process sent a malformed part");
      const int ab[2] = {received.a, received.b};
      const auto it = std::lower_bound(
          world.slots_.begin(), world.slots_.end(), std::pair<int, int>(ab[0], ab[1]),
          [](const World::PairSlot& x, const std::pair<int, int>& key) {
            return x.a < key.first || (x.a == key.first && x.b < key.second);
          });
      if (it == world.slots_.end() || it->a != ab[0] || it->b != ab[1])
        throw std::logic_error("pair exchange: a process sent a pair this one does not have");
      received.contact = it->contact;  // this process's old state, dropped by the settle
      received.pending = received.active;
      *it = received;
      if (received.active) {
        const auto k = static_cast<std::size_t>(it - world.slots_.begin());
        world.pending_[k / world.pending_run_].push_back({k, state});
        joined[k / world.pending_run_] = 1;
      }
    }
    dist_stats_.bytes_sent += static_cast<std::int64_t>(to[r].size());
    dist_stats_.bytes_received += static_cast<std::int64_t>(from[r].size());
  }
  for (std::size_t r = 0; r < world.pending_.size(); ++r) {
    if (joined[r] == 0) continue;
    std::sort(world.pending_[r].begin(), world.pending_[r].end(),
              [](const World::PendingContact& x, const World::PendingContact& y) {
                return x.slot < y.slot;
              });
  }
  world.settle_contacts();
  dist_stats_.bytes_sent += static_cast<std::int64_t>(head.size());
  dist_stats_.bytes_received += static_cast<std::int64_t>(heads.size() - head.size());
}

EnergyStepSums Decomposition::reduce_energy(World& world, StepScratch& s,
                                            const EnergyStepSums& mine) {
  const auto tw = std::chrono::steady_clock::now();
  const std::vector<std::int64_t> reduced = world.settings_.distribution->sum(mine.limbs());
  s.waiting += std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();
  const auto reduction_bytes = static_cast<std::int64_t>(reduced.size() * sizeof(std::int64_t));
  dist_stats_.bytes_sent += reduction_bytes;
  dist_stats_.bytes_received += reduction_bytes;
  return EnergyStepSums::from_limbs(reduced);
}

bool Decomposition::reduce_step_checks(World& world, StepScratch& s) {
  PairDistribution& dist = *world.settings_.distribution;
  // Ghosts for the next step, then the global checks: exact reductions (minima of indices and
  // time steps, integer sums).
  const auto tw = std::chrono::steady_clock::now();
  exchange_ghosts(world);
  double first_bad = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < own_list_.size() && std::isinf(first_bad); ++k) {
    const auto i = static_cast<std::size_t>(own_list_[k]);
    const Block& b = world.blocks_[i];
    if (!b.position.allFinite() || !b.velocity.allFinite() || !b.angular_velocity.allFinite() ||
        !b.orientation.coeffs().allFinite() || b.velocity.norm() > world.settings_.max_speed)
      first_bad = static_cast<double>(i);
  }
  const std::vector<double> minima = dist.min({s.dt_min, s.overlap_key, first_bad});
  const std::vector<std::int64_t> sums = dist.sum({s.active, s.broke});
  s.waiting += std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();
  world.contact_dt_ = std::isfinite(minima[0]) ? world.settings_.safety_factor * minima[0] : 0.0;
  overlap_key_ = minima[1];
  world.active_count_ = static_cast<std::size_t>(sums[0]);
  world.broken_bonds_ = s.broken_before + sums[1];
  if (sums[1] > 0) {
    // Which sets the bonds broken anywhere belong to: every process's table, summed (each has
    // the same rows: the face sets are the same everywhere).
    const std::size_t rows = world.break_table_rows();
    std::vector<std::int64_t> mine(2 * rows, 0);
    for (std::size_t k = 0; k < rows && k < world.step_breaks_.size(); ++k) {
      mine[2 * k] = world.step_breaks_[k][0];
      mine[2 * k + 1] = world.step_breaks_[k][1];
    }
    const std::vector<std::int64_t> all = dist.sum(mine);
    std::vector<std::array<std::int64_t, 2>> table(rows);
    for (std::size_t k = 0; k < rows; ++k) table[k] = {all[2 * k], all[2 * k + 1]};
    world.add_step_breaks(table);
  }
  replica_complete_ = false;
  dist_stats_.steps += 1;
  dist_stats_.owned_pairs += static_cast<std::int64_t>(s.mine.size());
  dist_stats_.pair_seconds += s.pair_seconds;
  dist_stats_.exchange_seconds += s.waiting;
  return std::isfinite(minima[1]) || std::isfinite(minima[2]);
}

void Decomposition::end_step(World& world, StepScratch& s) {
  // Rebalancing: every process sees the same measured figures, so all decide alike. The answers
  // do not depend on the partition, only the speed does.
  PairDistribution& dist = *world.settings_.distribution;
  const auto k_ranks = static_cast<double>(dist.size());
  const double mean = s.total / k_ranks;
  dist_stats_.last_imbalance = mean > 0.0 ? s.slowest / mean : 1.0;
  const std::int64_t since = world.step_count_ - partition_step_;
  const std::int64_t every = dist.repartition_interval();
  const double mean_pairs = s.total_pairs / k_ranks;
  const bool uneven_pairs = s.most_pairs > kPairCountThreshold * mean_pairs;
  if ((dist_stats_.last_imbalance > kImbalanceThreshold &&
       s.slowest - mean > kMinImbalanceSeconds && uneven_pairs &&
       since >= kMinStepsBetweenPartitions) ||
      (every > 0 && since >= every)) {
    if (deferred_replica_ && !replica_complete_) {
      migrate_blocks(world);  // point to point: no whole world
    } else {
      synchronize(world);  // made whole anyway at the step's end
      partition_blocks(world);
    }
  }
  if (!deferred_replica_) {
    synchronize(world);
  } else if (!replica_complete_) {
    release_spare_room(world);
  }
}

namespace {

// Whether a store keeps much more room than it uses (a quarter more, and at least 256 entries
// more): after the world was whole, a process's stores hold only its part of it.
template <class T>
bool release_spare(std::vector<T>& store) {
  if (store.capacity() - store.size() <= store.size() / 4 + 256) return false;
  store.shrink_to_fit();
  return true;
}

}  // namespace

void Decomposition::release_spare_room(World& world) {
  bool released = release_spare(world.slots_);
  released = release_spare(world.contacts_) || released;
  released = release_spare(world.pairs_) || released;
#if defined(__GLIBC__)
  // The C library keeps freed blocks of the heap for later allocations; the stores just shrunk
  // are most of what a process holds, so give their pages back to the system now (rare: after
  // the world was whole).
  if (released) malloc_trim(0);
#endif
}

}  // namespace blockdem
