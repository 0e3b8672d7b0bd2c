// The pair store's passes of a step over dense, sorted arrays: candidate pairs from the broad
// phase, a sorted merge that keeps each pair's slot, the per-pair work in parallel (each pair
// writes only its own slot and state; the pair's own work is in pair_response.cpp), and a sorted
// merge that keeps the contact states of the touching pairs, so that results are bit-identical
// for any number of threads (the loads' scatter: scatter_loads.cpp).
#include <algorithm>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "blockdem/response/contact_damping.hpp"
#include "blockdem/world/pair_changes.hpp"
#include "blockdem/world/pass_support.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

using namespace pass_support;

namespace {

bool less_pair(int a1, int b1, int a2, int b2) {
  return a1 < a2 || (a1 == a2 && b1 < b2);
}

// How many of the indices [0, n) satisfy `pred` (a count: the same for any split).
template <class Pred>
std::int64_t count_in_parallel(std::size_t n, int threads, const Pred& pred) {
  const auto m = static_cast<std::int64_t>(n);
  std::int64_t count = 0;
  if (threads < 2 || m <= 4096) {
    // No parallel region at all: even a team of one costs the runtime a futex call at its end.
    for (std::int64_t k = 0; k < m; ++k) count += pred(static_cast<std::size_t>(k)) ? 1 : 0;
    return count;
  }
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : count)
  for (std::int64_t k = 0; k < m; ++k) {
    if (pred(static_cast<std::size_t>(k))) ++count;
  }
  return count;
}

// How many slots are open bonds (`open`), and how many differ from the pair at their index.
template <typename Slot, typename Open>
std::pair<std::int64_t, std::int64_t> count_open_and_moved(
    const std::vector<Slot>& slots, const std::vector<std::pair<int, int>>& pairs, int threads,
    const Open& is_open) {
  const auto m = static_cast<std::int64_t>(slots.size());
  // 1 for an open bond, 2 for a slot that is not the pair's (the counts' own variables are
  // written in the loop: a lambda capturing them would bypass the reduction's private copies).
  const auto tally = [&](std::int64_t k) {
    const auto i = static_cast<std::size_t>(k);
    return (is_open(i) ? 1 : 0) |
           (slots[i].a != pairs[i].first || slots[i].b != pairs[i].second ? 2 : 0);
  };
  std::int64_t open = 0, differ = 0;
  if (threads < 2 || m <= 4096) {
    for (std::int64_t k = 0; k < m; ++k) {
      const int t = tally(k);
      open += t & 1;
      differ += t >> 1;
    }
    return {open, differ};
  }
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : open, differ)
  for (std::int64_t k = 0; k < m; ++k) {
    const int t = tally(k);
    open += t & 1;
    differ += t >> 1;
  }
  return {open, differ};
}

// The pair merge in parallel: the slots of `pairs` (sorted by (a, b), no repeats) take their
// places in `slots` (sorted, the pairs of the last step), each kept slot moved once; a pair
// that had no slot gets fresh(a, b). The arrangement is the serial merge's, for any thread
// count (move_slots, pair_changes.hpp). Each thread finds where each of its places' slot is now
// (a binary search for its first pair, then a merge walk) into a list of sources; `Index` holds
// a place of the old store and -1 (merge_in_parallel chooses the narrowest that does). Returns
// false, having changed nothing, after a large shift (the serial merge then).
template <typename Index, typename Fresh>
class ListWalk {
 public:
  ListWalk(const std::vector<Index>& source, const std::vector<std::pair<int, int>>& pairs,
           Fresh& fresh, std::size_t begin, std::size_t end)
      : source_(source), pairs_(pairs), fresh_(fresh), begin_(begin), end_(end) {}
  template <class F>
  void visit(bool increasing, F&& f) const {
    if (increasing) {
      for (std::size_t w = begin_; w < end_; ++w) f(w, std::int64_t{source_[w]}, w);
    } else {
      for (std::size_t w = end_; w-- > begin_;) f(w, std::int64_t{source_[w]}, w);
    }
  }
  auto make(std::int64_t, std::size_t w) const { return fresh_(pairs_[w].first, pairs_[w].second); }

 private:
  const std::vector<Index>& source_;
  const std::vector<std::pair<int, int>>& pairs_;
  Fresh& fresh_;
  std::size_t begin_, end_;
};

template <typename Index, typename Slot, typename Fresh>
bool merge_in_parallel_as(std::vector<Slot>& slots, const std::vector<std::pair<int, int>>& pairs,
                          int threads, Fresh&& fresh) {
  const std::size_t n_old = slots.size(), n_new = pairs.size();
  std::vector<Index> source(n_new);  // where each place's slot is now (-1: a new pair)
  const auto slot_less = [](const Slot& s, const std::pair<int, int>& p) {
    return less_pair(s.a, s.b, p.first, p.second);
  };
  return move_slots(slots, n_new, threads, [&](std::size_t begin, std::size_t end) {
    // The sources of the thread's places (the slots are only read).
    std::size_t k = n_old;
    if (begin < end) {
      k = static_cast<std::size_t>(
          std::lower_bound(slots.begin(), slots.begin() + static_cast<std::ptrdiff_t>(n_old),
                           pairs[begin], slot_less) -
          slots.begin());
    }
    for (std::size_t w = begin; w < end; ++w) {
      while (k < n_old && slot_less(slots[k], pairs[w])) ++k;
      const bool kept = k < n_old && slots[k].a == pairs[w].first && slots[k].b == pairs[w].second;
      source[w] = kept ? static_cast<Index>(k++) : Index{-1};
    }
    return ListWalk<Index, std::remove_reference_t<Fresh>>(source, pairs, fresh, begin, end);
  });
}

// The merge's list of sources in 4 bytes a place where the old store's places fit (at the step's
// peak with the pair list: 43 MB less for the 10.7 million pairs of a million-block rock mass).
template <typename Slot, typename Fresh>
bool merge_in_parallel(std::vector<Slot>& slots, const std::vector<std::pair<int, int>>& pairs,
                       int threads, Fresh&& fresh) {
  if (slots.size() < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    return merge_in_parallel_as<std::int32_t>(slots, pairs, threads, std::forward<Fresh>(fresh));
  return merge_in_parallel_as<std::int64_t>(slots, pairs, threads, std::forward<Fresh>(fresh));
}

}  // namespace

void World::find_step_pairs(StepScratch& s) {
  const int threads = s.threads;
  const std::vector<char> breakable = breakable_laws();
  // One process: the pairs by ranges of blocks, each range compared with its slots as it is
  // found, and only the changes kept (world_pairs.cpp): no list of every pair is made.
  PairChanges changes;
  // Prestressed joints that neither the broad phase nor a slot covers (a joint keeps its slot).
  std::vector<std::pair<int, int>> missed;
  const bool by_range = !s.distributed && find_pairs_by_range(threads, breakable, changes, missed);
  if (by_range) {
    if (missed.empty()) {
      take_primed_slots();  // drops the set-up's narrow phase (the store has slots)
      if (changes.none()) {
        // The common case of a settled scene: no range changed, the slots stay as they are.
        ++pair_list_counts_.unchanged;
        refresh_group_laws();
      } else {
        merge_pair_changes(changes);
      }
      return;
    }
    // A missed joint without a slot: the list after all (the ranges' pairs hold the open bonds'
    // and the other joints' already).
    ++pair_list_counts_.listed;
    list_changed_pairs(changes);
    merge_joints(missed);
    take_primed_slots();
    merge_pairs();
    std::vector<std::pair<int, int>>().swap(pairs_);
    return;
  }
  ++pair_list_counts_.joined;
  if (!by_range && !s.distributed) {
    // Broad phase: pairs where at least one block can move, sorted by (a, b). The list was
    // freed after the last merge: room for as many pairs as then, in one allocation.
    pairs_.reserve(slots_.size());
    pass_support::prefer_huge_pages(pairs_.data(), pairs_.capacity() * sizeof(pairs_[0]));
    broad_phase_.find_pairs(
        block_boxes(), [&](int a, int b) { return steps_pair(a, b); }, pairs_, threads);
  } else if (s.distributed) {
    // The pairs of this process's blocks (both blocks exact here); a resting block's pairs only
    // where the other block is this process's. The broad phase runs over the exact blocks'
    // boxes; as they are listed in index order, its pairs (i, j) of list places map to pairs of
    // blocks in the same order.
    broad_phase_.find_pairs(
        s.held_min, s.held_max,
        [&](int i, int j) {
          const int a = s.held[static_cast<std::size_t>(i)];
          const int b = s.held[static_cast<std::size_t>(j)];
          return (keeps_pairs_of(a) || keeps_pairs_of(b)) &&
                 (blocks_[a].motion != Motion::fixed || blocks_[b].motion != Motion::fixed) &&
                 (s.moves[static_cast<std::size_t>(a)] != 0 ||
                  s.moves[static_cast<std::size_t>(b)] != 0);
        },
        pairs_, threads);
    for (auto& [a, b] : pairs_) {
      a = s.held[static_cast<std::size_t>(a)];
      b = s.held[static_cast<std::size_t>(b)];
    }
    std::vector<Eigen::Vector3d>().swap(s.held_min);
    std::vector<Eigen::Vector3d>().swap(s.held_max);
  }
  // Prestressed joints keep their pairs: blocks that share an axis-aligned face may have boxes
  // that miss each other by round-off, and the joint is closed without the blocks overlapping.
  // Both lists are sorted by (a, b): one walk finds the joints' pairs the broad phase missed
  // (usually none), and only those are merged in, so that no second list of every pair is held.
  if (!preloads_.empty()) {
    std::size_t at = 0;
    for (const ContactPreload& p : preloads_.all()) {
      if (s.distributed && !keeps_pairs_of(p.a) && !keeps_pairs_of(p.b)) continue;
      const std::pair<int, int> pair{p.a, p.b};
      while (at < pairs_.size() && pairs_[at] < pair) ++at;
      if (at == pairs_.size() || pairs_[at] != pair) missed.push_back(pair);
    }
    merge_joints(missed);
  }
  // The common case of a settled scene, found in one pass over the slots (the pair store is
  // the largest array: each pass over it costs memory traffic that a second core barely
  // shortens): no open bond, and the same pairs as last step, whose slots then stay as they are.
  // Else no more passes than the open bonds' count and the merge's own comparison.
  bool same = false, no_open = false;
  if (!slots_.empty() && pairs_.size() == slots_.size()) {
    const auto [opened, differ] = count_open_and_moved(slots_, pairs_, threads, [&](std::size_t k) {
      return keeps_bond_pair(slots_[k], breakable);
    });
    no_open = opened == 0;
    same = no_open && differ == 0 && slots_rules_version_ == rules_version_;
  }
  if (!same) {
    if (!no_open) {
      keep_open_bonds(breakable);
      // A distributed step keeps an open bond's pair only where one of its blocks is kept here.
      if (s.distributed) {
        std::erase_if(pairs_, [&](const std::pair<int, int>& p) {
          return !keeps_pairs_of(p.first) && !keeps_pairs_of(p.second);
        });
      }
    }
    take_primed_slots();  // the set-up's narrow phase, at the first step
    merge_pairs();
  }
  // The slots now hold these pairs, in order: the list is not read again before the next broad
  // phase refills it, and freed it is not held through the step's peak (8 bytes per pair).
  if (!s.distributed) std::vector<std::pair<int, int>>().swap(pairs_);
}

void World::merge_joints(const std::vector<std::pair<int, int>>& missed) {
  if (missed.empty()) return;
  std::vector<std::pair<int, int>> all;
  all.reserve(pairs_.size() + missed.size());
  pass_support::prefer_huge_pages(all.data(), all.capacity() * sizeof(all[0]));
  std::merge(pairs_.begin(), pairs_.end(), missed.begin(), missed.end(), std::back_inserter(all));
  pairs_.swap(all);
}

bool World::keeps_bond_pair(const PairSlot& s, const std::vector<char>& breakable) const {
  if (!s.active) return false;
  const Contact& c = contact_of(s);
  return !c.touching || (c.shear.bond == BondState::intact && c.law >= 0 &&
                         breakable[static_cast<std::size_t>(c.law)] != 0);
}

std::vector<char> World::breakable_laws() const {
  std::vector<char> breakable(laws_.size());
  for (std::size_t l = 0; l < laws_.size(); ++l)
    breakable[l] = strength_of(laws_[l].shear).can_break() ? 1 : 0;
  return breakable;
}

void World::keep_open_bonds(const std::vector<char>& breakable) {
  // The broad phase finds pairs whose boxes touch; an open bond (an intact bonded contact whose
  // blocks have moved apart) keeps its pair after the boxes part, until it breaks. So does a
  // closed one that can open into tension: a joint compressed by less than its blocks move in a
  // step (a sudden unloading) parts its boxes before its bond has been tried in tension.
  // Counted first in parallel (a settled scene has none): the list is made only if needed.
  const auto keeps = [&](const PairSlot& s) { return keeps_bond_pair(s, breakable); };
  const auto is_open = [&](std::size_t k) { return keeps(slots_[k]); };
  if (count_in_parallel(slots_.size(), thread_count(), is_open) == 0) return;
  std::vector<std::pair<int, int>> open;
  for (const auto& s : slots_) {
    if (keeps(s)) open.emplace_back(s.a, s.b);
  }
  if (open.empty()) return;
  std::vector<std::pair<int, int>> all;
  all.reserve(pairs_.size() + open.size());
  std::set_union(pairs_.begin(), pairs_.end(), open.begin(), open.end(), std::back_inserter(all));
  pairs_.swap(all);
}

void World::merge_pairs() {
  // The common case: the same pairs as last step.
  bool same = pairs_.size() == slots_.size();
  if (same) {
    const auto differs = [&](std::size_t k) {
      return slots_[k].a != pairs_[k].first || slots_[k].b != pairs_[k].second;
    };
    same = count_in_parallel(pairs_.size(), thread_count(), differs) == 0;
  }
  const auto fresh = [&](int a, int b) { return fresh_slot(a, b); };
  const int threads = thread_count();
  bool merged = same;
  if (!merged && threads > 1 && pairs_.size() >= 256)
    merged = merge_in_parallel(slots_, pairs_, threads, fresh);
  if (!merged) {
    // Both lists are sorted by (a, b). First drop the slots whose pair is gone, compacting in
    // place (forward); then open the slots of new pairs, moving kept ones back (backward).
    std::size_t kept = 0, p = 0;
    for (std::size_t k = 0; k < slots_.size(); ++k) {
      const PairSlot& c = slots_[k];
      while (p < pairs_.size() && less_pair(pairs_[p].first, pairs_[p].second, c.a, c.b)) ++p;
      if (p < pairs_.size() && pairs_[p].first == c.a && pairs_[p].second == c.b) {
        if (kept != k) slots_[kept] = std::move(slots_[k]);
        ++kept;
      }
    }
    // Grow with an eighth of slack: the store is the largest array of a big scene, and a
    // doubling reallocation would briefly need three times its size.
    if (pairs_.size() > slots_.capacity()) slots_.reserve(pairs_.size() + pairs_.size() / 8);
    slots_.resize(std::max(kept, pairs_.size()));
    std::size_t old = kept;  // slots [0, kept) hold a subset of pairs_, in order
    for (std::size_t w = pairs_.size(); w-- > 0;) {
      const auto [a, b] = pairs_[w];
      if (old > 0 && slots_[old - 1].a == a && slots_[old - 1].b == b) {
        --old;
        if (old != w) slots_[w] = std::move(slots_[old]);
      } else {
        slots_[w] = fresh_slot(a, b);
      }
    }
    slots_.resize(pairs_.size());
  }
  refresh_group_laws();
}

World::PairSlot World::fresh_slot(int a, int b) const {
  // A new candidate pair: the joint law is looked up once, when the pair appears. Its contact
  // state (none yet) stays where it was: settle_contacts drops it. Bonds (rock bridges) join
  // only blocks that were candidates at the start: a pair that becomes one later has never
  // been bonded and gets the residual strength.
  PairSlot fresh;
  fresh.a = a;
  fresh.b = b;
  fresh.group_law = law_for(a, b);
  if (step_count_ > 0) fresh.bond = BondState::unbonded;
  return fresh;
}

void World::refresh_group_laws() {
  if (slots_rules_version_ == rules_version_) return;
  for (auto& s : slots_) s.group_law = law_for(s.a, s.b);
  slots_rules_version_ = rules_version_;
}

Contact World::fresh_contact(const PairSlot& slot) const {
  Contact c;
  c.a = slot.a;
  c.b = slot.b;
  c.law = slot.group_law;
  c.shear.bond = slot.bond;
  return c;
}

std::exception_ptr World::evaluate_slots(double dt, bool advance_shear, int threads,
                                         const std::vector<char>* only) {
  const std::size_t n = slots_.size();
  // Runs of slots, each one thread's work at a time and each with its own list of new contact
  // states (in slot order); the run length changes where the states wait, not the results.
  const std::size_t parts = static_cast<std::size_t>(std::max(threads, 1)) * 16;
  pending_run_ = std::clamp<std::size_t>(n / parts + 1, 64, 4096);
  const std::size_t runs = (n + pending_run_ - 1) / pending_run_;
  pending_.clear();
  pending_.resize(runs);
  // No slot has a state yet (the first step, a restore): every state is new and goes to the
  // end of the store, in slot order. The runs are then taken a few per thread at a time and
  // each wave's lists are appended and freed before the next wave, so that the lists and the
  // store are never both whole in memory. The store is reserved for every slot: only the pages
  // the states fill are touched (a settled pile has ~1.5 slots per state).
  const bool all_new = contacts_.empty();
  const std::size_t wave =
      all_new ? static_cast<std::size_t>(std::max(threads, 1)) * 4 : std::max<std::size_t>(runs, 1);
  if (all_new) contacts_.reserve(n);
  // An exception inside the parallel loop is kept (the one of the first pair in order) and
  // returned after it, as a serial loop would.
  std::size_t failed = n;
  std::exception_ptr error;
  // Contact damping: the last step's dashpots' second halves of work, with the velocities that
  // step gave the blocks (one exact sum per run: the same bits for any thread count). Nothing
  // is read per slot when no contact had a dashpot.
  const bool dashpots = advance_shear && (settings_.contact_damping > 0.0 || dashpots_last_step_);
  std::vector<ExactSum> carried(dashpots ? runs : 0);
  const auto carry_dashpot = [&](Contact& ct, ExactSum& sum) {
    if (ct.damping_force() != 0.0) sum.add(dashpot_carried(ct));
    ct.set_damping(0.0, 0.0);
  };
  for (std::size_t first = 0; first < runs; first += wave) {
    const std::int64_t wave_end = static_cast<std::int64_t>(std::min(runs, first + wave));
    const auto evaluate_run = [&](std::int64_t r) {
      const std::size_t begin = static_cast<std::size_t>(r) * pending_run_;
      const std::size_t end = std::min(n, begin + pending_run_);
      std::vector<PendingContact> formed;
      for (std::size_t i = begin; i < end; ++i) {
        // With a block's record its list of face laws, and with its planes the laws themselves
        // (a rock mass's blocks have them; a pile's none).
        if (i + kPrefetchRecord < end) {
          const PairSlot& ahead = slots_[i + kPrefetchRecord];
          prefetch_record(blocks_[static_cast<std::size_t>(ahead.b)]);
          face_laws_.prefetch_run(static_cast<std::size_t>(ahead.b));
          if (ahead.a != slots_[i + kPrefetchRecord - 1].a)
            prefetch_record(blocks_[static_cast<std::size_t>(ahead.a)]);
        }
        if (i + kPrefetchPlanes < end) {
          const PairSlot& ahead = slots_[i + kPrefetchPlanes];
          prefetch_planes(blocks_[static_cast<std::size_t>(ahead.b)]);
          face_laws_.prefetch_values(static_cast<std::size_t>(ahead.b));
          if (ahead.a != slots_[i + kPrefetchPlanes - 1].a)
            prefetch_planes(blocks_[static_cast<std::size_t>(ahead.a)]);
        }
        if (only != nullptr && (*only)[i] == 0) continue;
        PairSlot& slot = slots_[i];
        if (dashpots && slot.contact >= 0)
          carry_dashpot(contact_of(slot), carried[static_cast<std::size_t>(r)]);
        try {
          if (slot.contact >= 0) {
            Contact& ct = contact_of(slot);
            evaluate_pair(slot, ct, dt, advance_shear);
            slot.pending = false;
            if (!slot.active) slot.bond = ct.shear.bond;  // the state goes at settle_contacts
          } else {
            Contact ct = fresh_contact(slot);
            evaluate_pair(slot, ct, dt, advance_shear);
            slot.pending = slot.active;
            if (slot.active) {
              formed.push_back({i, std::move(ct)});
            } else {
              slot.bond = ct.shear.bond;
            }
          }
        } catch (...) {
          slot.active = false;  // no state to read: the step fails
          slot.pending = false;
#pragma omp critical(blockdem_pair_error)
          if (i < failed) {
            failed = i;
            error = std::current_exception();
          }
        }
      }
      // Exactly the size needed.
      pending_[static_cast<std::size_t>(r)].assign(std::make_move_iterator(formed.begin()),
                                                   std::make_move_iterator(formed.end()));
    };
    // No parallel region for one thread: a team of one still costs a futex call at its end.
    if (threads > 1 && runs > 1) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
      for (std::int64_t r = static_cast<std::int64_t>(first); r < wave_end; ++r) evaluate_run(r);
    } else {
      for (std::int64_t r = static_cast<std::int64_t>(first); r < wave_end; ++r) evaluate_run(r);
    }
    if (!all_new) continue;
    for (std::size_t r = first; r < static_cast<std::size_t>(wave_end); ++r) {
      for (PendingContact& p : pending_[r]) {
        PairSlot& s = slots_[p.slot];
        s.pending = false;
        s.contact = static_cast<std::int32_t>(contacts_.size());
        contacts_.push_back(std::move(p.contact));
      }
      std::vector<PendingContact>().swap(pending_[r]);
    }
  }
  // After a restart, the halves the checkpoint kept (its contacts have no dashpot values).
  dashpot_carried_ = ExactSum{};
  if (advance_shear) std::swap(dashpot_carried_, dashpot_restored_);
  for (const ExactSum& sum : carried) dashpot_carried_ += sum;
  if (advance_shear) dashpots_last_step_ = settings_.contact_damping > 0.0;
  return error;
}

double World::dashpot_carried(const Contact& ct) const {
  return -dashpot_carried_work(ct.damping_force(), blocks_[static_cast<std::size_t>(ct.a)],
                               blocks_[static_cast<std::size_t>(ct.b)], ct.force_point(),
                               ct.geometry.normal, last_dt_);
}

ExactSum World::dashpot_pending() const {
  ExactSum sum;
  for (const PairSlot& s : slots_) {
    if (s.contact < 0) continue;
    const Contact& ct = contact_of(s);
    if (ct.damping_force() != 0.0) sum.add(dashpot_carried(ct));
  }
  return sum;
}

void World::evaluate_pairs(double dt, bool advance_shear, int threads) {
  const std::exception_ptr error = evaluate_slots(dt, advance_shear, threads);
  settle_contacts();
  if (error) std::rethrow_exception(error);
}

void World::settle_contacts() {
  // Each slot's state goes to its place in slot order among the kept and new states: the
  // (kept + new) states before it. The slots are cut into one run per thread; a run's old
  // states lie in its own range of the store, range[t] to range[t + 1] (the store is in slot
  // order), and their new places from places[t] on. Within its range a run moves the
  // states that go down in increasing order and those that go up in decreasing order (no state
  // is overwritten before it is moved), in two walks over its slots; the few whose new place is
  // outside the range (about as many as states formed or dropped before the run) are copied
  // aside in the first walk and written last, with the new states placed outside the range,
  // after every run has moved its own. Each walk reads the 120-byte slots of the run: walks
  // are memory traffic, which a second core barely shortens.
  const int threads = thread_count();
  if (threads < 2 || slots_.size() < 256 || !settle_contacts_parallel(threads))
    settle_contacts_serial();
}

bool World::settle_contacts_parallel(int threads) {
  const std::size_t m = slots_.size();
  std::size_t kept_total = 0, runs_used = 1;
  std::vector<std::size_t> kept(static_cast<std::size_t>(threads), 0);
  std::vector<std::size_t> formed(kept.size(), 0), old_first(kept.size(), contacts_.size());
  std::vector<std::size_t> places(kept.size() + 1, 0), range(kept.size() + 1, contacts_.size());
  std::vector<std::vector<std::pair<std::size_t, Contact>>> aside(kept.size());
  bool all_new = false, unchanged = false, missing = false;
#pragma omp parallel num_threads(threads)
  {
    const auto runs = static_cast<std::size_t>(team_size());
    const auto t = static_cast<std::size_t>(team_rank());
    const std::size_t begin = t * m / runs, end = (t + 1) * m / runs;
    // 1. Counts, and the run's first old state (kept locally: no shared cache lines).
    std::size_t my_kept = 0, my_formed = 0, my_first = contacts_.size();
    for (std::size_t k = begin; k < end; ++k) {
      const PairSlot& s = slots_[k];
      if (s.contact >= 0 && my_first == contacts_.size())
        my_first = static_cast<std::size_t>(s.contact);
      if (s.pending) {
        ++my_formed;
      } else if (s.contact >= 0 && s.active) {
        ++my_kept;
      }
    }
    kept[t] = my_kept;
    formed[t] = my_formed;
    old_first[t] = my_first;
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t r = 0; r < runs; ++r) {
        places[r + 1] = places[r] + kept[r] + formed[r];
        kept_total += kept[r];
      }
      for (std::size_t r = runs; r-- > 0;) range[r] = std::min(old_first[r], range[r + 1]);
      all_new = kept_total == 0;
      runs_used = runs;
      const std::size_t total = places[runs];
      // Every state kept and none formed (a scene at rest): each stays at its index, as
      // the store is in slot order, and the walks below would move nothing.
      unchanged = !all_new && total == kept_total && kept_total == contacts_.size();
      if (!all_new && !unchanged) {
        if (total > contacts_.capacity()) contacts_.reserve(total + total / 8);
        if (total > contacts_.size()) contacts_.resize(total);
      }
    }
    if (!all_new && !unchanged) {
      const std::size_t from = range[t], to = range[t + 1];
      const auto inside = [&](std::size_t w) { return w >= from && w < to; };
      // The new state of pending slot k, taken from its run's list.
      const auto take_new = [&](std::size_t k, std::size_t w) {
        std::vector<PendingContact>& list = pending_[k / pending_run_];
        const auto it = std::lower_bound(
            list.begin(), list.end(), k,
            [](const PendingContact& p, std::size_t slot) { return p.slot < slot; });
        if (it == list.end() || it->slot != k) {
#pragma omp atomic write
          missing = true;
        } else {
          contacts_[w] = std::move(it->contact);
        }
      };
      // 2. Forward: kept states whose new place is outside the run's range, aside; those going
      // down within it, moved (in increasing order). Only the run's own range is read or
      // written until the barrier: the states of a run's slots lie in its range.
      std::size_t w = places[t];
      for (std::size_t k = begin; k < end; ++k) {
        const PairSlot& s = slots_[k];
        if (s.pending) {
          ++w;
        } else if (s.contact >= 0 && s.active) {
          const auto o = static_cast<std::size_t>(s.contact);
          if (!inside(w)) {
            aside[t].emplace_back(w, std::move(contacts_[o]));
          } else if (w < o) {
            contacts_[w] = std::move(contacts_[o]);
          }
          ++w;
        }
      }
      // 3. Backward: those going up (in decreasing order), and the new states whose place is
      // in the range (every state of a later slot has left it or reached its place by then;
      // one of an earlier slot there has moved down or aside). The slots take their places.
      std::vector<std::pair<std::size_t, std::size_t>> new_outside;  // (slot, place)
      for (std::size_t k = end; k-- > begin;) {
        PairSlot& s = slots_[k];
        if (s.pending) {
          --w;
          if (inside(w)) {
            take_new(k, w);
          } else {
            new_outside.emplace_back(k, w);
          }
          s.pending = false;
          s.contact = static_cast<std::int32_t>(w);
        } else if (s.contact >= 0 && s.active) {
          const auto o = static_cast<std::size_t>(s.contact);
          --w;
          if (inside(w) && w > o) contacts_[w] = std::move(contacts_[o]);
          s.contact = static_cast<std::int32_t>(w);
        } else {
          s.contact = -1;
        }
      }
#pragma omp barrier
      // 4. The states set aside and the new states placed outside the range.
      for (auto& [place, state] : aside[t]) contacts_[place] = std::move(state);
      for (const auto& [k, place] : new_outside) take_new(k, place);
    }
  }
  if (all_new) return false;
  if (missing) throw std::logic_error("contact merge: a new contact state is missing");
  const std::size_t total = places[runs_used];
  contacts_.resize(total);
  pending_.clear();
  if (contacts_.capacity() > 2 * total + 1024) pass_support::release_spare_room(contacts_);
  return true;
}

void World::settle_contacts_serial() {
  // Forward: the kept states of active slots move down over those of inactive or gone slots
  // (both in slot order, so a state never moves up).
  std::size_t kept = 0, formed = 0;
  for (PairSlot& s : slots_) {
    if (s.contact >= 0 && s.active && !s.pending) {
      if (static_cast<std::size_t>(s.contact) != kept)
        contacts_[kept] = std::move(contacts_[static_cast<std::size_t>(s.contact)]);
      s.contact = static_cast<std::int32_t>(kept++);
    } else {
      s.contact = -1;
    }
    if (s.pending) ++formed;
  }
  const std::size_t total = kept + formed;
  if (total > contacts_.capacity()) contacts_.reserve(total + total / 8);
  if (kept == 0) {
    // Every state is new, though some slots had one before: appended run by run, each run's
    // list freed once taken.
    contacts_.clear();
    for (std::vector<PendingContact>& list : pending_) {
      for (PendingContact& p : list) {
        PairSlot& s = slots_[p.slot];
        s.pending = false;
        s.contact = static_cast<std::int32_t>(contacts_.size());
        contacts_.push_back(std::move(p.contact));
      }
      std::vector<PendingContact>().swap(list);
    }
    pending_.clear();
    if (contacts_.size() != total)
      throw std::logic_error("contact merge: a new contact state is missing");
    return;
  }
  // Backward: the new states take their places between the kept ones, each run's list freed
  // once taken (only the store's new tail is touched).
  contacts_.resize(total);
  std::size_t w = total;
  for (std::size_t k = slots_.size(); k-- > 0;) {
    PairSlot& s = slots_[k];
    if (s.pending) {
      std::vector<PendingContact>& list = pending_[k / pending_run_];
      if (list.empty() || list.back().slot != k)
        throw std::logic_error("contact merge: a new contact state is missing");
      contacts_[--w] = std::move(list.back().contact);
      list.pop_back();
      if (list.empty()) std::vector<PendingContact>().swap(list);
      s.pending = false;
      s.contact = static_cast<std::int32_t>(w);
    } else if (s.contact >= 0) {
      if (static_cast<std::size_t>(s.contact) != --w)
        contacts_[w] = std::move(contacts_[static_cast<std::size_t>(s.contact)]);
      s.contact = static_cast<std::int32_t>(w);
    }
  }
  pending_.clear();
  if (contacts_.capacity() > 2 * total + 1024) pass_support::release_spare_room(contacts_);
}

void World::compact_contacts() {
  std::size_t kept = 0;
  for (PairSlot& s : slots_) {
    if (s.contact < 0) continue;
    if (static_cast<std::size_t>(s.contact) != kept)
      contacts_[kept] = std::move(contacts_[static_cast<std::size_t>(s.contact)]);
    s.contact = static_cast<std::int32_t>(kept++);
  }
  contacts_.resize(kept);
}

}  // namespace blockdem
