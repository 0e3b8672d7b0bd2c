// A one-process step's broad phase without a list of every pair. The grid hands over the pairs
// of each range of blocks (UniformGrid::find_pairs_by_range) and the slots hold last step's pairs
// sorted by (a, b), so each range's pairs are compared with its run of slots where they are found,
// and only what changed is kept (pair_changes.hpp); merge_pair_changes then rearranges the store
// from the changes.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "blockdem/world/pair_changes.hpp"
#include "blockdem/world/world.hpp"

namespace blockdem {

bool World::find_pairs_by_range(int threads, const std::vector<char>& breakable,
                                PairChanges& changes, std::vector<std::pair<int, int>>& missed) {
  // The first step (no slots yet) has nothing to compare with: the threads' lists, joined.
  if (slots_.empty()) return false;
  const std::int64_t n = static_cast<std::int64_t>(blocks_.size());
  const std::int64_t size = UniformGrid::kRangeBoxes;
  const auto ranges = static_cast<std::size_t>((n + size - 1) / size);
  // Where each range's slots start: the first slot whose block a is the range's first (the
  // last range's end is the store's end, so that every slot is in a range).
  changes.slot_at.assign(ranges + 1, slots_.size());
  for (std::size_t r = 0; r < ranges; ++r) {
    const int first = static_cast<int>(static_cast<std::int64_t>(r) * size);
    changes.slot_at[r] = static_cast<std::size_t>(
        std::lower_bound(slots_.begin(), slots_.end(), first,
                         [](const PairSlot& s, int a) { return s.a < a; }) -
        slots_.begin());
  }
  changes.ranges.assign(ranges, RangeChange{});
  // Each range's prestressed joints (sorted by (a, b) as the pairs), and those of them that the
  // range's new pairs miss (find_step_pairs: blocks that share an axis-aligned face may have
  // boxes that miss each other by round-off).
  const std::span<const ContactPreload> joints = preloads_.all();
  std::vector<std::size_t> joint_at(ranges + 1, joints.size());
  for (std::size_t r = 0; r < ranges && !joints.empty(); ++r) {
    const int first = static_cast<int>(static_cast<std::int64_t>(r) * size);
    joint_at[r] = static_cast<std::size_t>(
        std::lower_bound(joints.begin(), joints.end(), first,
                         [](const ContactPreload& p, int a) { return p.a < a; }) -
        joints.begin());
  }
  std::vector<std::vector<std::pair<int, int>>> missed_of(ranges);
  const auto take = [&](std::int64_t begin, std::int64_t, const auto& pairs) {
    const auto r = static_cast<std::size_t>(begin / size);
    const std::size_t lo = changes.slot_at[r], hi = changes.slot_at[r + 1];
    const std::size_t j_end = joint_at[r + 1];
    // A slot whose boxes parted keeps its pair while it holds an open bond (keep_open_bonds),
    // and a prestressed joint's slot keeps its pair always, as the joined list merges the
    // joints in: its pair is then among the range's new run, not missed. The slots come in
    // increasing order, so one cursor over the range's joints finds each.
    std::size_t kept_joint = joint_at[r];
    const auto keep = [&](const PairSlot& s) {
      const std::uint64_t key = pair_key(s.a, s.b);
      while (kept_joint < j_end && pair_key(joints[kept_joint].a, joints[kept_joint].b) < key)
        ++kept_joint;
      if (kept_joint < j_end && pair_key(joints[kept_joint].a, joints[kept_joint].b) == key)
        return true;
      return keeps_bond_pair(s, breakable);
    };
    // The joints before each new pair that no pair matched, then those after the last (pairs
    // and joints compared by their keys): those without a slot.
    std::size_t j = joint_at[r];
    std::uint64_t next = j < j_end ? pair_key(joints[j].a, joints[j].b) : kNoPair;
    const auto pass = [&](int a, int b) {
      const std::uint64_t pair = pair_key(a, b);
      while (next <= pair) {
        if (next < pair) missed_of[r].emplace_back(joints[j].a, joints[j].b);
        ++j;
        next = j < j_end ? pair_key(joints[j].a, joints[j].b) : kNoPair;
      }
    };
    diff_range(slots_.data() + lo, hi - lo, pairs, keep, pass, changes.ranges[r]);
    pass(std::numeric_limits<int>::max(), std::numeric_limits<int>::max());
  };
  if (!broad_phase_.find_pairs_by_range(
          block_boxes(), [&](int a, int b) { return steps_pair(a, b); }, take, threads)) {
    changes = PairChanges{};
    return false;
  }
  for (const auto& m : missed_of) missed.insert(missed.end(), m.begin(), m.end());
  return true;
}

void World::list_changed_pairs(const PairChanges& changes) {
  std::size_t total = 0;
  for_each_changed_pair(slots_, changes, [&](int, int) { ++total; });
  pairs_.clear();
  pairs_.reserve(total);
  pass_support::prefer_huge_pages(pairs_.data(), pairs_.capacity() * sizeof(pairs_[0]));
  for_each_changed_pair(slots_, changes, [&](int a, int b) { pairs_.emplace_back(a, b); });
}

void World::merge_pair_changes(const PairChanges& changes) {
  const auto fresh = [&](int a, int b) { return fresh_slot(a, b); };
  if (merge_changes(slots_, changes, thread_count(), fresh)) {
    ++pair_list_counts_.changed;
    refresh_group_laws();
    return;
  }
  // A large shift (more than an eighth of the slots would cross between the threads' places):
  // the list, merged serially.
  ++pair_list_counts_.listed;
  list_changed_pairs(changes);
  merge_pairs();
  std::vector<std::pair<int, int>>().swap(pairs_);
}

}  // namespace blockdem
