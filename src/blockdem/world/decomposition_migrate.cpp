// A rebalance without the whole world: each block that changes owner goes point to point to its
// new owner with the pair slots it lacks, then one ghost exchange for the new subdomains.
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

namespace blockdem {

using namespace decomposition_wire;

/// The blocks and slots a process received in a migration, the slots' contact states apart.
struct Decomposition::Arrivals {
  std::vector<World::PairSlot> slots;
  std::vector<Contact> states;
};

std::vector<int> Decomposition::migration_owners(World& world, std::int64_t& sent,
                                                 std::int64_t& received) {
  PairDistribution& dist = *world.settings_.distribution;
  const auto k_ranks = static_cast<std::size_t>(dist.size());
  const std::size_t n = world.blocks_.size();
  // 1. The partition's input, as partition_blocks() takes it from a whole world: each
  // block's centroid, whether it is at rest (mark_resting), and the number of slots it is in. Its
  // owner holds them exactly: after the step's pair exchange every slot of an own block that is not
  // resting is here, exact (the pair's owner, which is one of the two blocks' owners, sent it),
  // and no slot is here twice. A record of 28 bytes per block, gathered to every process in the
  // order of the owners' block lists, which every process knows (owner_).
  std::vector<std::uint32_t> pair_count(n, 0);
  for (const World::PairSlot& s : world.slots_) {
    for (const int i : {s.a, s.b})
      if (own_[static_cast<std::size_t>(i)] != 0) ++pair_count[static_cast<std::size_t>(i)];
  }
  constexpr std::size_t kInput = 3 * sizeof(double) + sizeof(std::uint32_t);
  std::vector<char> input;
  input.reserve(own_list_.size() * kInput);
  for (const int h : own_list_) {
    const auto i = static_cast<std::size_t>(h);
    if (pair_count[i] > (std::numeric_limits<std::uint32_t>::max() >> 1))
      throw std::logic_error("migration: a block in too many pairs");
    put3(input, world.blocks_[i].position);
    put(input,
        static_cast<std::uint32_t>(pair_count[i] << 1 | (at_rest(world.blocks_[i]) ? 1u : 0u)));
  }
  std::vector<std::size_t> counts;
  const std::vector<char> inputs = dist.all_gather(input, counts);
  sent += static_cast<std::int64_t>(input.size());
  received += static_cast<std::int64_t>(inputs.size() - input.size());
  std::vector<std::uint32_t>().swap(pair_count);
  std::vector<std::size_t> cursor(k_ranks, 0);
  for (std::size_t r = 1; r < k_ranks; ++r) cursor[r] = cursor[r - 1] + counts[r - 1];
  std::vector<Eigen::Vector3d> points(n);
  std::vector<double> weights(n, 1.0);
  bool rest_changed = false;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(owner_[i]);
    std::size_t& at = cursor[r];
    if (at + kInput > inputs.size())
      throw std::logic_error("migration: a process sent a malformed partition input");
    points[i] = get3(inputs, at);
    const auto word = get<std::uint32_t>(inputs, at + 24);
    at += kInput;
    const bool resting = (word & 1u) != 0;
    rest_changed = rest_changed || resting != (resting_[i] != 0);
    // 1 + the pair count, as partition_blocks adds 1.0 per slot (exact: integers).
    if (!resting) weights[i] += static_cast<double>(word >> 1);
  }
  for (std::size_t r = 0, end = 0; r < k_ranks; ++r) {
    end += counts[r];
    if (cursor[r] != end)
      throw std::logic_error("migration: a process sent a malformed partition input");
  }
  // A block came to rest or left it (a caller's change, or a servo that stopped a fixed block):
  // no migration (the caller makes the world whole and partitions it).
  if (rest_changed) return {};
  std::vector<int> owners = dist.partition(points, weights);
  if (owners.size() != n) throw std::logic_error("partition: one owner per block expected");

  return owners;
}

std::vector<std::vector<char>> Decomposition::migration_messages(World& world,
                                                                 const std::vector<int>& owners,
                                                                 std::int64_t& sent) {
  const int rank = world.settings_.distribution->rank();
  const auto k_ranks = static_cast<std::size_t>(world.settings_.distribution->size());
  // 2. Each own block whose owner changes, to its new owner: its state, loads, stiffness sums,
  // energy record, world planes and box (what a refresh would send; a divergence checkpoint in
  // parts stays as it is, gathered from the parts as they were saved). Its servo and applied
  // loads change only on a whole world, alike everywhere. With it, its slots (contact states
  // included) that the new owner does not hold exactly: all but those whose other block that
  // process owns and does not rest. The new owner needs every slot of its blocks that do not
  // rest: its own pairs among them, and the others' for the loads' sums in (a, b) order.
  std::vector<std::vector<char>> block_part(k_ranks), slot_part(k_ranks);
  std::vector<std::uint64_t> blocks_to(k_ranks, 0), slots_to(k_ranks, 0);
  for (const int h : own_list_) {
    const auto i = static_cast<std::size_t>(h);
    const auto q = static_cast<std::size_t>(owners[i]);
    if (static_cast<int>(q) == rank) continue;
    put_block_state(world, block_part[q], i);
    ++blocks_to[q];
  }
  const auto moving_to = [&](int block) {
    const auto i = static_cast<std::size_t>(block);
    return own_[i] != 0 && resting_[i] == 0 && owners[i] != rank ? owners[i] : -1;
  };
  const auto holds = [&](int q, int block) {
    const auto i = static_cast<std::size_t>(block);
    return owner_[i] == q && resting_[i] == 0;
  };
  for (const World::PairSlot& s : world.slots_) {
    const int qa = moving_to(s.a), qb = moving_to(s.b);
    if (qa < 0 && qb < 0) continue;
    const Contact* state = s.active ? &world.contact_of(s) : nullptr;
    if (qa >= 0 && !holds(qa, s.b)) {
      put_slot(slot_part[static_cast<std::size_t>(qa)], s, state);
      ++slots_to[static_cast<std::size_t>(qa)];
    }
    if (qb >= 0 && qb != qa && !holds(qb, s.a)) {
      put_slot(slot_part[static_cast<std::size_t>(qb)], s, state);
      ++slots_to[static_cast<std::size_t>(qb)];
    }
  }
  std::vector<std::vector<char>> to(k_ranks);
  for (std::size_t q = 0; q < k_ranks; ++q) {
    if (blocks_to[q] == 0 && slots_to[q] == 0) continue;
    to[q].reserve(16 + block_part[q].size() + slot_part[q].size());
    put(to[q], blocks_to[q]);
    put(to[q], slots_to[q]);
    put_bytes(to[q], block_part[q].data(), block_part[q].size());
    put_bytes(to[q], slot_part[q].data(), slot_part[q].size());
    std::vector<char>().swap(block_part[q]);
    std::vector<char>().swap(slot_part[q]);
    dist_stats_.migrated_blocks += static_cast<std::int64_t>(blocks_to[q]);
    dist_stats_.migrated_slots += static_cast<std::int64_t>(slots_to[q]);
    sent += static_cast<std::int64_t>(to[q].size());
  }
  return to;
}

Decomposition::Arrivals Decomposition::receive_migrated(World& world,
                                                        const std::vector<std::vector<char>>& from,
                                                        const std::vector<int>& owners,
                                                        std::int64_t& received) {
  const int rank = world.settings_.distribution->rank();
  const auto k_ranks = from.size();
  const std::size_t n = world.blocks_.size();
  // 3. The received blocks into place; the received slots in a list, their states apart.
  world.stiffness_.resize(n, 0.0);
  world.rotational_stiffness_.resize(n, 0.0);
  world.energy_.prepare(n);
  Arrivals in;
  std::vector<World::PairSlot>& arrived = in.slots;
  std::vector<Contact>& arrived_states = in.states;
  for (std::size_t r = 0; r < k_ranks; ++r) {
    const std::vector<char>& part = from[r];
    received += static_cast<std::int64_t>(part.size());
    if (part.empty()) continue;
    if (part.size() < 16) throw std::logic_error("migration: a process sent a malformed part");
    const auto blocks_in = get<std::uint64_t>(part, 0);
    const auto slots_in = get<std::uint64_t>(part, 8);
    std::size_t at = 16;
    for (std::uint64_t k = 0; k < blocks_in; ++k) {
      std::size_t i = 0;
      at = take_block_state(world, part, at, part.size(), true, i);
      if (owner_[i] != static_cast<int>(r) || owners[i] != rank)
        throw std::logic_error("migration: a block came from a process that did not own it");
    }
    for (std::uint64_t k = 0; k < slots_in; ++k) {
      World::PairSlot s;
      Contact c;
      if (!get_slot(part, at, part.size(), s, c))
        throw std::logic_error("migration: a process sent a malformed part");
      s.pending = false;
      s.contact = -1;
      if (s.active) {
        s.contact = static_cast<std::int32_t>(arrived_states.size());
        arrived_states.push_back(c);
      }
      arrived.push_back(s);
    }
    if (at != part.size()) throw std::logic_error("migration: a process sent a malformed part");
  }

  return in;
}

void Decomposition::keep_migrated_slots(World& world, Arrivals& in) {
  const int rank = world.settings_.distribution->rank();
  const std::size_t n = world.blocks_.size();
  std::vector<World::PairSlot>& arrived = in.slots;
  std::vector<Contact>& arrived_states = in.states;
  // 5. The slots as a step leaves them: those of the blocks this process now keeps (own, not
  // resting), in (a, b) order, every one exact; the contact states in slot order. A pair that
  // arrived from two processes (its blocks came from both) holds the same bytes in both.
  const auto keeps = [&](int block) {
    const auto i = static_cast<std::size_t>(block);
    return own_[i] != 0 && resting_[i] == 0;
  };
  const auto kept = [&](const World::PairSlot& s) { return keeps(s.a) || keeps(s.b); };
  std::erase_if(world.slots_, [&](const World::PairSlot& s) { return !kept(s); });
  const auto before = [](const World::PairSlot& x, const World::PairSlot& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  };
  std::sort(arrived.begin(), arrived.end(), before);
  std::vector<World::PairSlot> slots;
  slots.reserve(world.slots_.size() + arrived.size());
  std::vector<Contact> contacts;
  std::size_t p = 0;
  for (std::size_t q = 0; q <= arrived.size(); ++q) {
    // The held slots before the next arrived one (all of them after the last), then that one
    // unless held or already taken.
    while (p < world.slots_.size() &&
           (q == arrived.size() || !before(arrived[q], world.slots_[p]))) {
      World::PairSlot s = world.slots_[p++];
      if (s.active) {
        contacts.push_back(world.contact_of(s));
        s.contact = static_cast<std::int32_t>(contacts.size() - 1);
      } else {
        s.contact = -1;
      }
      slots.push_back(s);
    }
    if (q == arrived.size()) break;
    World::PairSlot s = arrived[q];
    if (!slots.empty() && slots.back().a == s.a && slots.back().b == s.b) continue;
    if (!kept(s)) throw std::logic_error("migration: a slot of no block this process keeps");
    if (s.active) {
      contacts.push_back(arrived_states[static_cast<std::size_t>(s.contact)]);
      s.contact = static_cast<std::int32_t>(contacts.size() - 1);
    }
    slots.push_back(s);
  }
  world.slots_ = std::move(slots);
  world.contacts_ = std::move(contacts);
  std::vector<World::PairSlot>().swap(arrived);
  std::vector<Contact>().swap(arrived_states);
  world.pairs_.resize(world.slots_.size());
  for (std::size_t k = 0; k < world.slots_.size(); ++k)
    world.pairs_[k] = {world.slots_[k].a, world.slots_[k].b};
  world.overlap_violation_ =
      slot_of_key(world.slots_, n, overlap_key_,
                  [&](const World::PairSlot& c) { return pair_owner(world, c.a, c.b) == rank; });
}

void Decomposition::migrate_blocks(World& world) {
  const int rank = world.settings_.distribution->rank();
  const std::size_t n = world.blocks_.size();
  const auto t0 = std::chrono::steady_clock::now();
  std::int64_t sent = 0, received = 0;
  std::vector<int> owners = migration_owners(world, sent, received);
  if (owners.empty()) {
    // A block came to rest or left it (a caller's change, or a servo that stopped a fixed block):
    // the resting blocks' loads are summed only on a whole world, so every process (all see the
    // same flags) makes it whole and partitions it.
    dist_stats_.migration_bytes_sent += sent;
    dist_stats_.migration_bytes_received += received;
    synchronize(world);
    partition_blocks(world);
    return;
  }
  std::vector<std::vector<char>> to = migration_messages(world, owners, sent);
  const std::vector<std::vector<char>> from = world.settings_.distribution->exchange(to);
  std::vector<std::vector<char>>().swap(to);
  Arrivals in = receive_migrated(world, from, owners, received);

  // 4. The new owners.
  owner_ = std::move(owners);
  for (std::size_t i = 0; i < n; ++i) own_[i] = owner_[i] == rank ? 1 : 0;
  list_own_blocks(world);
  partition_step_ = world.step_count_;
  ++dist_stats_.partitions;

  keep_migrated_slots(world, in);

  // 6. Ghosts for the next step, for the new subdomains: the ghost exchange with the slots' sends
  // (an own block to the owner of its pair's other block, neither resting) listed as the step
  // lists them.
  pair_sends_.clear();
  for (const World::PairSlot& c : world.slots_) {
    const auto ca = static_cast<std::size_t>(c.a), cb = static_cast<std::size_t>(c.b);
    if ((own_[ca] != 0 && own_[cb] != 0) || resting_[ca] != 0 || resting_[cb] != 0) continue;
    if (own_[ca] != 0) pair_sends_.emplace_back(c.a, owner_[cb]);
    if (own_[cb] != 0) pair_sends_.emplace_back(c.b, owner_[ca]);
  }
  const std::int64_t ghost_sent = dist_stats_.bytes_sent,
                     ghost_received = dist_stats_.bytes_received;
  ghosts_listed_ = false;
  exchange_ghosts(world);
  sent += dist_stats_.bytes_sent - ghost_sent;
  received += dist_stats_.bytes_received - ghost_received;
  dist_stats_.bytes_sent = ghost_sent;
  dist_stats_.bytes_received = ghost_received;

  dist_stats_.migrations += 1;
  dist_stats_.migration_bytes_sent += sent;
  dist_stats_.migration_bytes_received += received;
  dist_stats_.migration_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace blockdem
