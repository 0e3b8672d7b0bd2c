// The pair store's changes by ranges (world/pair_changes.hpp) against std::set_union: each range's
// change, the pairs it lists and the store merged from the changes on 1, 2 and 3 threads are the
// sorted union of the new pairs and the slots kept open, every kept slot moved whole.
#include "blockdem/world/pair_changes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <random>
#include <set>
#include <utility>
#include <vector>

// A namespace of this file's own: the unity build compiles it with other test files.
namespace blockdem::test::pair_changes_test {
namespace {

struct Slot {
  int a = -1, b = -1;
  int id = -1;        // the old store's place; -1: made fresh
  bool open = false;  // kept when its pair is gone
};

using Pairs = std::vector<std::pair<int, int>>;

// Sorted pairs (a < b < blocks) drawn at random, no repeats.
Pairs random_pairs(std::mt19937& rng, int blocks, std::size_t count) {
  std::uniform_int_distribution<int> block(0, blocks - 1);
  std::set<std::pair<int, int>> set;
  while (set.size() < count) {
    const int a = block(rng), b = block(rng);
    if (a != b) set.emplace(std::min(a, b), std::max(a, b));
  }
  return Pairs(set.begin(), set.end());
}

// The changes of `slots` to `pairs` in ranges of `size` blocks, each range's new run as
// diff_range lists it appended to `listed`.
PairChanges changes_of(const std::vector<Slot>& slots, const Pairs& pairs, int blocks, int size,
                       Pairs& listed) {
  const auto ranges = static_cast<std::size_t>((blocks + size - 1) / size);
  PairChanges c;
  c.slot_at.assign(ranges + 1, slots.size());
  c.ranges.resize(ranges);
  for (std::size_t r = 0; r < ranges; ++r) {
    c.slot_at[r] = static_cast<std::size_t>(
        std::lower_bound(slots.begin(), slots.end(), static_cast<int>(r) * size,
                         [](const Slot& s, int a) { return s.a < a; }) -
        slots.begin());
  }
  for (std::size_t r = 0; r < ranges; ++r) {
    Pairs range_pairs;
    for (const auto& p : pairs)
      if (p.first / size == static_cast<int>(r)) range_pairs.push_back(p);
    const std::size_t lo = c.slot_at[r], hi = c.slot_at[r + 1];
    diff_range(
        slots.data() + lo, hi - lo, range_pairs, [](const Slot& s) { return s.open; },
        [&](int a, int b) { listed.emplace_back(a, b); }, c.ranges[r]);
  }
  return c;
}

// The oracle: the new pairs' union with the open slots' pairs.
Pairs union_with_open(const std::vector<Slot>& slots, const Pairs& pairs) {
  Pairs open;
  for (const Slot& s : slots)
    if (s.open) open.emplace_back(s.a, s.b);
  Pairs out;
  std::set_union(pairs.begin(), pairs.end(), open.begin(), open.end(), std::back_inserter(out));
  return out;
}

std::vector<Slot> store_of(const Pairs& pairs, std::mt19937& rng) {
  std::vector<Slot> slots;
  std::bernoulli_distribution open(0.1);
  for (const auto& [a, b] : pairs)
    slots.push_back({a, b, static_cast<int>(slots.size()), open(rng)});
  return slots;
}

// Oracle: std::set_union. Tolerance: none (indices and pairs). Old stores and new pair lists
// that keep most pairs and trade a few (a settled step), and ones that share few (a big
// rearrangement), with ranges of 8 blocks (some empty).
TEST(PairChanges, MergedStoreIsTheUnionOfThePairsAndTheOpenSlots) {
  std::mt19937 rng(7);
  const int blocks = 300;
  for (int trial = 0; trial < 40; ++trial) {
    const Pairs old_pairs = random_pairs(rng, blocks, 2000);
    const std::vector<Slot> old_store = store_of(old_pairs, rng);
    // A new list: most old pairs kept (a settled step) or few (a rearrangement), some new.
    const double keep = trial % 4 == 3 ? 0.2 : 0.98;
    std::bernoulli_distribution kept(keep);
    std::set<std::pair<int, int>> next;
    for (const auto& p : old_pairs)
      if (kept(rng)) next.insert(p);
    for (const auto& p : random_pairs(rng, blocks, trial % 4 == 3 ? 1500 : 40)) next.insert(p);
    const Pairs pairs(next.begin(), next.end());
    const Pairs expected = union_with_open(old_store, pairs);

    Pairs listed;
    const PairChanges c = changes_of(old_store, pairs, blocks, 8, listed);
    EXPECT_EQ(listed, expected) << "trial " << trial;
    EXPECT_EQ(c.new_at().back(), expected.size());
    Pairs walked;
    for_each_changed_pair(old_store, c, [&](int a, int b) { walked.emplace_back(a, b); });
    EXPECT_EQ(walked, expected) << "trial " << trial;

    for (int threads : {1, 2, 3}) {
      std::vector<Slot> store = old_store;
      const bool merged = merge_changes(store, c, threads, [](int a, int b) {
        return Slot{a, b, -1, false};
      });
      if (!merged) {
        // Declined (too many slots cross between the threads' places): nothing changed.
        EXPECT_GT(threads, 1);
        ASSERT_EQ(store.size(), old_store.size());
        for (std::size_t k = 0; k < store.size(); ++k) EXPECT_EQ(store[k].id, old_store[k].id);
        continue;
      }
      ASSERT_EQ(store.size(), expected.size()) << "trial " << trial << ", " << threads;
      for (std::size_t k = 0; k < store.size(); ++k) {
        const Slot& s = store[k];
        ASSERT_EQ(std::make_pair(s.a, s.b), expected[k]) << "trial " << trial << ", place " << k;
        // A kept slot is the old one, whole; a slot is fresh only where the pair is new.
        const auto old = std::lower_bound(old_pairs.begin(), old_pairs.end(), expected[k]);
        if (old != old_pairs.end() && *old == expected[k]) {
          const auto place = static_cast<std::size_t>(old - old_pairs.begin());
          EXPECT_EQ(s.id, static_cast<int>(place));
          EXPECT_EQ(s.open, old_store[place].open);
        } else {
          EXPECT_EQ(s.id, -1);
        }
      }
    }
  }
}

// A range that gains many pairs at the store's start shifts every later slot across the second
// thread's places: on 2 threads the merge declines and leaves the store as it was; on one
// thread it merges.
TEST(PairChanges, LargeShiftDeclinedOnTwoThreadsMergedOnOne) {
  Pairs old_pairs;
  for (int a = 8; a < 200; ++a) old_pairs.emplace_back(a, a + 1);
  std::mt19937 rng(3);
  std::vector<Slot> old_store = store_of(old_pairs, rng);
  for (Slot& s : old_store) s.open = false;
  Pairs pairs = old_pairs;
  for (int b = 1; b < 100; ++b) pairs.emplace_back(0, b);  // range 0 gains 99 pairs
  std::sort(pairs.begin(), pairs.end());
  Pairs listed;
  const PairChanges c = changes_of(old_store, pairs, 201, 8, listed);
  ASSERT_EQ(listed, pairs);
  std::vector<Slot> store = old_store;
  const auto fresh = [](int a, int b) { return Slot{a, b, -1, false}; };
  EXPECT_FALSE(merge_changes(store, c, 2, fresh));
  ASSERT_EQ(store.size(), old_store.size());
  for (std::size_t k = 0; k < store.size(); ++k) EXPECT_EQ(store[k].id, old_store[k].id);
  ASSERT_TRUE(merge_changes(store, c, 1, fresh));
  ASSERT_EQ(store.size(), pairs.size());
  for (std::size_t k = 0; k < store.size(); ++k) {
    EXPECT_EQ(std::make_pair(store[k].a, store[k].b), pairs[k]);
    EXPECT_EQ(store[k].id, k < 99 ? -1 : static_cast<int>(k - 99));
  }
}

}  // namespace
}  // namespace blockdem::test::pair_changes_test
