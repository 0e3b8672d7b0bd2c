// A step's candidate pairs as changes of the last step's, range by range, and the merge of the
// pair store that reads them (world_pairs.cpp finds them). The broad phase hands over the pairs
// of each range of blocks (UniformGrid::find_pairs_by_range); the store holds last step's pairs
// sorted by (a, b), so a range's slots are one run of the store. Each range keeps only what
// changed: the places of its slots whose pair is gone and its new pairs with their places. A
// settled million-block rock mass (10.7 million pairs, each range gaining or losing a few a
// step) held a list of every pair (86 MB) and the merge's source of each place (43 MB) at the
// step's peak; its changes take a few hundred kilobytes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "blockdem/world/pass_support.hpp"

namespace blockdem {

/// A pair (a, b) of block indices (>= 0) as one number that sorts as (a, b) does.
inline std::uint64_t pair_key(int a, int b) {
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32 |
         static_cast<std::uint32_t>(b);
}
/// Above every pair's key.
inline constexpr std::uint64_t kNoPair = ~std::uint64_t{0};

/// One range's pairs against its slots. Both lists empty: the range's pairs are its slots'.
struct RangeChange {
  /// Places (from the range's first slot) of the slots whose pair is gone, increasing.
  std::vector<std::uint32_t> gone;
  /// A pair the slots did not have, and its place in the range's new run.
  struct Added {
    std::uint32_t at = 0;
    int a = -1, b = -1;
  };
  std::vector<Added> added;  ///< by place, increasing
  bool none() const { return gone.empty() && added.empty(); }
};

/// The step's pairs as every range's change of the store.
struct PairChanges {
  /// Where each range's slots start in the store, and the store's end (ranges + 1 entries).
  std::vector<std::size_t> slot_at;
  std::vector<RangeChange> ranges;
  std::size_t range_count() const { return ranges.size(); }
  bool none() const {
    return std::all_of(ranges.begin(), ranges.end(), [](const RangeChange& c) { return c.none(); });
  }
  /// Where each range's new run starts, and the new store's size (ranges + 1 entries).
  std::vector<std::size_t> new_at() const {
    std::vector<std::size_t> at(ranges.size() + 1, 0);
    for (std::size_t r = 0; r < ranges.size(); ++r) {
      const RangeChange& c = ranges[r];
      at[r + 1] = at[r] + (slot_at[r + 1] - slot_at[r]) - c.gone.size() + c.added.size();
    }
    return at;
  }
  /// The sources of range r's new run, in order: a slot's place in the store (>= 0), or
  /// -1 - k for the range's k-th added pair.
  void sources(std::size_t r, std::vector<std::int64_t>& out) const {
    const RangeChange& c = ranges[r];
    const std::size_t old = slot_at[r + 1] - slot_at[r];
    const std::size_t count = old - c.gone.size() + c.added.size();
    out.resize(count);
    std::size_t k = 0, g = 0, n = 0;
    for (std::size_t j = 0; j < count; ++j) {
      if (n < c.added.size() && c.added[n].at == j) {
        out[j] = -1 - static_cast<std::int64_t>(n++);
        continue;
      }
      while (g < c.gone.size() && c.gone[g] == k) ++g, ++k;
      out[j] = static_cast<std::int64_t>(slot_at[r] + k++);
    }
  }
};

/// Range r's change: the merge walk of its slots [slots, slots + count) (sorted by (a, b)) and
/// its pairs (sorted, no repeats). A slot whose pair is gone stays when keep(slot) says so (an
/// open bond keeps its pair after the boxes part: World::keep_open_bonds). on_pair(a, b) is
/// called for each pair of the range's new run, in order.
template <class Slot, class Keep, class OnPair>
void diff_range(const Slot* slots, std::size_t count, const std::vector<std::pair<int, int>>& pairs,
                Keep&& keep, OnPair&& on_pair, RangeChange& out) {
  out.gone.clear();
  out.added.clear();
  std::size_t k = 0, i = 0;
  std::uint32_t at = 0;  // the next place of the new run
  while (k < count || i < pairs.size()) {
    const std::uint64_t slot = k < count ? pair_key(slots[k].a, slots[k].b) : kNoPair;
    const std::uint64_t pair =
        i < pairs.size() ? pair_key(pairs[i].first, pairs[i].second) : kNoPair;
    if (slot < pair) {
      if (keep(slots[k])) {
        on_pair(slots[k].a, slots[k].b);
        ++at;
      } else {
        out.gone.push_back(static_cast<std::uint32_t>(k));
      }
      ++k;
      continue;
    }
    on_pair(pairs[i].first, pairs[i].second);
    if (pair < slot) {
      out.added.push_back({at, pairs[i].first, pairs[i].second});
    } else {
      ++k;
    }
    ++at, ++i;
  }
}

/// Every pair of the new store in order: f(a, b), from the slots and the changes.
template <class Slot, class F>
void for_each_changed_pair(const std::vector<Slot>& slots, const PairChanges& changes, F&& f) {
  std::vector<std::int64_t> source;
  for (std::size_t r = 0; r < changes.range_count(); ++r) {
    if (changes.ranges[r].none()) {
      for (std::size_t k = changes.slot_at[r]; k < changes.slot_at[r + 1]; ++k)
        f(slots[k].a, slots[k].b);
      continue;
    }
    changes.sources(r, source);
    for (const std::int64_t s : source) {
      if (s >= 0) {
        f(slots[static_cast<std::size_t>(s)].a, slots[static_cast<std::size_t>(s)].b);
      } else {
        const RangeChange::Added& p = changes.ranges[r].added[static_cast<std::size_t>(-1 - s)];
        f(p.a, p.b);
      }
    }
  }
}

/// The store's slots moved into their new places in place, on `threads` threads, each kept slot
/// moved once: the parallel part of the pair merge, whatever lists the new places. Each thread
/// owns a range [begin, end) of the n_new new places; plan(begin, end) makes, on that thread
/// and while the store is only read, its walk: an object whose visit(increasing, f) calls
/// f(w, source, key) for each place w of the range in increasing or decreasing order (source:
/// the old place of w's slot, or < 0 for a pair without a slot; key: what the walk's
/// make(source, key) needs to make that pair's slot). The thread copies aside the slots it
/// takes from outside its range and, after a barrier (no thread reads outside its range again),
/// moves the slots of its range: those going down in increasing order, then those going up in
/// decreasing order. As both the old and the new places are sorted by pair, a slot going down
/// never lands where one going up still is, and the reverse, so no slot is overwritten before it
/// moves. Returns false, having changed nothing, if more than an eighth of the slots would be
/// copied aside (a large shift, as after a big rearrangement: the caller then merges serially,
/// which needs no room for them).
template <class Slot, class Plan>
bool move_slots(std::vector<Slot>& slots, std::size_t n_new, int threads, Plan&& plan) {
  const auto runs = static_cast<std::size_t>(std::max(threads, 1));
  std::vector<std::size_t> aside_count(runs, 0);
  std::vector<std::vector<std::pair<std::size_t, Slot>>> aside(runs);
  bool too_many = false;
#pragma omp parallel num_threads(static_cast <int>(runs))
  {
    const auto t = static_cast<std::size_t>(pass_support::team_rank());
    const auto team = static_cast<std::size_t>(pass_support::team_size());
    const std::size_t begin = t * n_new / team, end = (t + 1) * n_new / team;
    const auto inside = [&](std::int64_t k) {
      return k >= static_cast<std::int64_t>(begin) && k < static_cast<std::int64_t>(end);
    };
    auto walk = plan(begin, end);
    // 1. The slots this thread takes from outside its places (the store is only read).
    std::size_t outside = 0;
    walk.visit(true, [&](std::size_t, std::int64_t s, std::size_t) {
      if (s >= 0 && !inside(s)) ++outside;
    });
    aside_count[t] = outside;
#pragma omp barrier
#pragma omp single
    {
      std::size_t total = 0;
      for (const std::size_t c : aside_count) total += c;
      too_many = total > n_new / 8;
      // Room for every place (the places past the old end are moved into or made fresh).
      if (!too_many && n_new > slots.size()) {
        if (n_new > slots.capacity()) slots.reserve(n_new + n_new / 8);
        slots.resize(n_new);
      }
    }
    if (!too_many) {
      // 2. Those slots, aside.
      aside[t].reserve(aside_count[t]);
      walk.visit(true, [&](std::size_t w, std::int64_t s, std::size_t) {
        if (s >= 0 && !inside(s))
          aside[t].emplace_back(w, std::move(slots[static_cast<std::size_t>(s)]));
      });
#pragma omp barrier
      // 3. Within the places: down in increasing order, then up in decreasing order.
      walk.visit(true, [&](std::size_t w, std::int64_t s, std::size_t) {
        if (inside(s) && static_cast<std::size_t>(s) > w)
          slots[w] = std::move(slots[static_cast<std::size_t>(s)]);
      });
      walk.visit(false, [&](std::size_t w, std::int64_t s, std::size_t) {
        if (inside(s) && static_cast<std::size_t>(s) < w)
          slots[w] = std::move(slots[static_cast<std::size_t>(s)]);
      });
      // 4. The slots set aside, and the slots of the pairs that had none.
      for (auto& [place, slot] : aside[t]) slots[place] = std::move(slot);
      std::vector<std::pair<std::size_t, Slot>>().swap(aside[t]);
      walk.visit(true, [&](std::size_t w, std::int64_t s, std::size_t key) {
        if (s < 0) slots[w] = walk.make(s, key);
      });
    }
  }
  if (too_many) return false;
  slots.resize(n_new);
  return true;
}

/// merge_changes's walk over one thread's new places, range by range: a range that did not
/// change has its slots shifted, another its sources worked out from its changes when the walk
/// reaches it (move_slots's plan).
template <class Fresh>
class ChangesWalk {
 public:
  ChangesWalk(const PairChanges& changes, const std::vector<std::size_t>& new_at, Fresh& fresh,
              std::size_t begin, std::size_t end)
      : changes_(changes), new_at_(new_at), fresh_(fresh), begin_(begin), end_(end) {}
  template <class F>
  void visit(bool increasing, F&& f) {
    if (begin_ == end_) return;
    const std::size_t ranges = changes_.range_count();
    const std::size_t first = static_cast<std::size_t>(
        std::upper_bound(new_at_.begin(), new_at_.end(), begin_) - new_at_.begin() - 1);
    std::size_t last = first;
    while (last + 1 < ranges && new_at_[last + 1] < end_) ++last;
    for (std::size_t i = 0; i <= last - first; ++i) {
      const std::size_t r = increasing ? first + i : last - i;
      const std::size_t lo = std::max(begin_, new_at_[r]), hi = std::min(end_, new_at_[r + 1]);
      const bool same = changes_.ranges[r].none();
      if (!same) changes_.sources(r, source_);
      const auto source_of = [&](std::size_t w) {
        return same ? static_cast<std::int64_t>(w - new_at_[r] + changes_.slot_at[r])
                    : source_[w - new_at_[r]];
      };
      if (increasing) {
        for (std::size_t w = lo; w < hi; ++w) f(w, source_of(w), r);
      } else {
        for (std::size_t w = hi; w-- > lo;) f(w, source_of(w), r);
      }
    }
  }
  /// The slot of range r's added pair -1 - s.
  auto make(std::int64_t s, std::size_t r) const {
    const RangeChange::Added& p = changes_.ranges[r].added[static_cast<std::size_t>(-1 - s)];
    return fresh_(p.a, p.b);
  }

 private:
  const PairChanges& changes_;
  const std::vector<std::size_t>& new_at_;
  Fresh& fresh_;
  std::size_t begin_, end_;
  std::vector<std::int64_t> source_;  // one changed range's
};

/// The store rearranged into the new pairs' order in place (move_slots): each kept slot moved
/// once, an added pair's slot fresh(a, b). The arrangement is the sorted merge's for any thread
/// count: the store holds the new pairs sorted by (a, b). As merge_in_parallel
/// (world_contacts.cpp), but the source of each place comes from the changes when it is needed
/// instead of a list of them. Returns false, having changed nothing, if more than an eighth of
/// the slots would be copied aside (the caller then merges a list serially).
template <class Slot, class Fresh>
bool merge_changes(std::vector<Slot>& slots, const PairChanges& changes, int threads,
                   Fresh&& fresh) {
  const std::vector<std::size_t> new_at = changes.new_at();
  return move_slots(
      slots, new_at[changes.range_count()], threads, [&](std::size_t begin, std::size_t end) {
        return ChangesWalk<std::remove_reference_t<Fresh>>(changes, new_at, fresh, begin, end);
      });
}

}  // namespace blockdem
