// A one-process step's broad phase without a second list of every pair. The grid hands over the
// pairs of each range of blocks (UniformGrid::find_pairs_by_range), and the slots hold last
// step's pairs sorted by (a, b), so a range's pairs are its slots' exactly when the two sorted
// runs are equal. A range that differs writes its pairs straight into the pair list, in a window
// as long as its slots plus some room; the windows are then closed up in order. A million-block
// rock mass (10.7 million candidate pairs, most ranges gaining or losing a few each step) held
// the list (86 MB) and, while the threads' lists were joined into it, those lists too, at the
// step's peak. The room is 5 % of the list there (a thirty-second of each range's slots and 64
// pairs); the windows are written whole, so the list is as resident as a list of every pair.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "blockdem/world/pass_support.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

bool World::find_pairs_by_range(int threads, const std::vector<char>& breakable, std::int64_t& open,
                                bool& slots_pairs) {
  // The first step (no slots yet) has no windows to size: the threads' lists, joined.
  if (slots_.empty()) return false;
  const std::int64_t n = static_cast<std::int64_t>(blocks_.size());
  const std::int64_t size = UniformGrid::kRangeBoxes;
  const auto ranges = static_cast<std::size_t>((n + size - 1) / size);
  // Where each range's slots start: the first slot whose block a is the range's first (the
  // last range's end is the store's end, so that every slot is in a range). Its window in the
  // list: its slots' count and a thirty-second more, plus 64 pairs.
  std::vector<std::size_t> slot_at(ranges + 1, slots_.size());
  std::vector<std::size_t> window_at(ranges + 1, 0);
  for (std::size_t r = 0; r < ranges; ++r) {
    const int first = static_cast<int>(static_cast<std::int64_t>(r) * size);
    slot_at[r] = static_cast<std::size_t>(
        std::lower_bound(slots_.begin(), slots_.end(), first,
                         [](const PairSlot& s, int a) { return s.a < a; }) -
        slots_.begin());
  }
  for (std::size_t r = 0; r < ranges; ++r) {
    const std::size_t count = slot_at[r + 1] - slot_at[r];
    window_at[r + 1] = window_at[r] + count + count / 32 + 64;
  }
  pairs_.clear();
  pairs_.reserve(window_at[ranges]);
  pass_support::prefer_huge_pages(pairs_.data(), pairs_.capacity() * sizeof(pairs_[0]));
  pairs_.resize(window_at[ranges]);
  // Per range: -1 when its pairs are its slots', else their count (in its window, or in
  // `overflow` when more than the window holds).
  std::vector<std::int64_t> count_of(ranges, -1);
  std::vector<std::vector<std::pair<int, int>>> overflow(ranges);
  std::vector<std::int64_t> open_of(static_cast<std::size_t>(std::max(threads, 1)), 0);
  const auto take = [&](std::int64_t begin, std::int64_t, const auto& pairs) {
    const auto r = static_cast<std::size_t>(begin / size);
    const std::size_t lo = slot_at[r], hi = slot_at[r + 1];
    // One walk over the range's slots: the open bonds (counted over every slot, as the step's
    // other passes count them) and whether the slots are these pairs.
    bool equal = hi - lo == pairs.size();
    std::int64_t opened = 0;
    for (std::size_t k = lo; k < hi; ++k) {
      const PairSlot& slot = slots_[k];
      opened += keeps_bond_pair(slot, breakable) ? 1 : 0;
      if (equal) equal = slot.a == pairs[k - lo].first && slot.b == pairs[k - lo].second;
    }
    open_of[static_cast<std::size_t>(pass_support::team_rank())] += opened;
    if (equal) return;
    count_of[r] = static_cast<std::int64_t>(pairs.size());
    if (pairs.size() > window_at[r + 1] - window_at[r]) {
      overflow[r] = pairs;
    } else {
      std::copy(pairs.begin(), pairs.end(),
                pairs_.begin() + static_cast<std::ptrdiff_t>(window_at[r]));
    }
  };
  if (!broad_phase_.find_pairs_by_range(
          block_boxes(), [&](int a, int b) { return steps_pair(a, b); }, take, threads)) {
    std::vector<std::pair<int, int>>().swap(pairs_);
    return false;
  }
  open = 0;
  for (const std::int64_t o : open_of) open += o;
  slots_pairs = std::all_of(count_of.begin(), count_of.end(), [](std::int64_t c) { return c < 0; });
  if (slots_pairs) {
    pairs_.clear();
    ++pair_list_counts_.slots_own;
    return true;
  }
  const bool overflowed =
      std::any_of(overflow.begin(), overflow.end(), [](const auto& o) { return !o.empty(); });
  // Every pair, in order: a range that differs gives its own pairs, another its slots' pairs.
  const auto range_into = [&](std::size_t r, std::pair<int, int>* to) {
    if (count_of[r] < 0) {
      for (std::size_t k = slot_at[r]; k < slot_at[r + 1]; ++k) *to++ = {slots_[k].a, slots_[k].b};
      return slot_at[r + 1] - slot_at[r];
    }
    const auto count = static_cast<std::size_t>(count_of[r]);
    const std::pair<int, int>* from =
        overflow[r].empty() ? pairs_.data() + window_at[r] : overflow[r].data();
    if (from != to) std::copy(from, from + count, to);  // down: overlapping is safe
    std::vector<std::pair<int, int>>().swap(overflow[r]);
    return count;
  };
  if (!overflowed) {
    // In place: a range's pairs end no later than its window ends, so moving them down in order
    // overwrites only windows already read.
    std::size_t at = 0;
    for (std::size_t r = 0; r < ranges; ++r) at += range_into(r, pairs_.data() + at);
    pairs_.resize(at);
    ++pair_list_counts_.in_place;
    return true;
  }
  // A range gained more pairs than its room (a large rearrangement): a list of its own.
  std::size_t total = 0;
  for (std::size_t r = 0; r < ranges; ++r)
    total += count_of[r] < 0 ? slot_at[r + 1] - slot_at[r] : static_cast<std::size_t>(count_of[r]);
  std::vector<std::pair<int, int>> all(total);
  std::size_t at = 0;
  for (std::size_t r = 0; r < ranges; ++r) at += range_into(r, all.data() + at);
  pairs_.swap(all);
  ++pair_list_counts_.own_list;
  return true;
}

}  // namespace blockdem
