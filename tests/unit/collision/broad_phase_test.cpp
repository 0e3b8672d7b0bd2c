// Tests of the sweep-and-prune broad phase: the same pairs as testing every pair, for random boxes,
// a tall column and a long wall, while the boxes move between calls; the sweep follows the
// longest extent of the set.
#include "blockdem/collision/broad_phase.hpp"
#include "blockdem/collision/uniform_grid.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/random_shapes.hpp"

namespace blockdem {
namespace {

using test_shapes::Rng;
using test_shapes::uniform;

using Pairs = std::vector<std::pair<int, int>>;

// Every pair (i < j) whose closed boxes overlap on all three axes and for which i + j is not a
// multiple of 7 (a filter, to check that `want` is honoured).
Pairs brute_force(const std::vector<Eigen::Vector3d>& lo, const std::vector<Eigen::Vector3d>& hi) {
  Pairs out;
  for (int i = 0; i < static_cast<int>(lo.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(lo.size()); ++j) {
      bool overlap = true;
      for (int k = 0; k < 3; ++k) overlap = overlap && lo[j][k] <= hi[i][k] && lo[i][k] <= hi[j][k];
      if (overlap && (i + j) % 7 != 0) out.emplace_back(i, j);
    }
  }
  return out;
}

Pairs sweep(SweepAndPrune& sap, const std::vector<Eigen::Vector3d>& lo,
            const std::vector<Eigen::Vector3d>& hi) {
  Pairs out;
  sap.find_pairs(
      lo, hi, [](int i, int j) { return (i + j) % 7 != 0; }, out);
  std::sort(out.begin(), out.end());
  return out;
}

// Boxes of unit size at the given centres, jittered.
void boxes(const std::vector<Eigen::Vector3d>& centres, Rng& rng, std::vector<Eigen::Vector3d>& lo,
           std::vector<Eigen::Vector3d>& hi) {
  lo.clear();
  hi.clear();
  for (const Eigen::Vector3d& c : centres) {
    const Eigen::Vector3d half(uniform(rng, 0.4, 0.6), uniform(rng, 0.4, 0.6),
                               uniform(rng, 0.4, 0.6));
    lo.push_back(c - half);
    hi.push_back(c + half);
  }
}

TEST(SweepAndPrune, SamePairsAsBruteForceAndSweepsAlongTheLongestExtent) {
  Rng rng(10);
  struct Layout {
    const char* name;
    int expected_axis;  // -1: any
  };
  for (const Layout layout : {Layout{"cloud", -1}, Layout{"column", 2}, Layout{"wall", 1}}) {
    SweepAndPrune sap;
    std::vector<Eigen::Vector3d> centres;
    for (int i = 0; i < 300; ++i) {
      if (layout.expected_axis == 2) {
        centres.emplace_back(uniform(rng, -0.1, 0.1), uniform(rng, -0.1, 0.1), 0.95 * i);
      } else if (layout.expected_axis == 1) {
        centres.emplace_back(uniform(rng, -0.1, 0.1), 0.95 * (i % 60), 0.95 * (i / 60));
      } else {
        centres.emplace_back(uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, -4, 4));
      }
    }
    std::vector<Eigen::Vector3d> lo, hi;
    for (int call = 0; call < 20; ++call) {
      // The boxes drift between calls (the sweep order is repaired, not rebuilt).
      for (Eigen::Vector3d& c : centres) c += 0.05 * test_shapes::random_unit_vector(rng);
      boxes(centres, rng, lo, hi);
      const Pairs expected = brute_force(lo, hi);
      ASSERT_EQ(sweep(sap, lo, hi), expected) << layout.name << " call " << call;
      if (layout.expected_axis >= 0) {
        EXPECT_EQ(sap.axis(), layout.expected_axis) << layout.name;
      }
    }
    EXPECT_FALSE(brute_force(lo, hi).empty());
  }
}

// Both broad phases against testing every pair (the oracle), for a random cloud, a tall column,
// a wide 3D pile of similar boxes and a pile on a large base plate (tested against every box):
// the same pairs, sorted by (i, j) as they come out (no sort here), for 1, 2 and 3 threads.
TEST(BroadPhase, GridAndSweepGiveSortedBruteForcePairsForAnyThreadCount) {
  Rng rng(11);
  for (const char* layout : {"cloud", "column", "pile", "pile on plate"}) {
    std::vector<Eigen::Vector3d> centres;
    for (int i = 0; i < 600; ++i) {
      if (std::string(layout) == "cloud") {
        centres.emplace_back(uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, -4, 4));
      } else if (std::string(layout) == "column") {
        centres.emplace_back(uniform(rng, -0.1, 0.1), uniform(rng, -0.1, 0.1), 0.95 * i);
      } else {
        centres.emplace_back(0.97 * (i % 12), 0.97 * ((i / 12) % 10), 0.97 * (i / 120));
      }
    }
    std::vector<Eigen::Vector3d> lo, hi;
    UniformGrid grid;
    SweepAndPrune sap;
    for (int call = 0; call < 5; ++call) {
      for (Eigen::Vector3d& c : centres) c += 0.05 * test_shapes::random_unit_vector(rng);
      boxes(centres, rng, lo, hi);
      if (std::string(layout) == "pile on plate") {
        lo[7] = Eigen::Vector3d(-1, -1, -1.5);
        hi[7] = Eigen::Vector3d(13, 11, -0.45);
      }
      const Pairs expected = brute_force(lo, hi);
      ASSERT_FALSE(expected.empty());
      for (int threads : {1, 2, 3}) {
        Pairs from_grid, from_sweep;
        grid.find_pairs(
            lo, hi, [](int i, int j) { return (i + j) % 7 != 0; }, from_grid, threads);
        sap.find_pairs(
            lo, hi, [](int i, int j) { return (i + j) % 7 != 0; }, from_sweep, threads);
        EXPECT_EQ(from_grid, expected) << layout << " call " << call << " threads " << threads;
        EXPECT_EQ(from_sweep, expected) << layout << " call " << call << " threads " << threads;
      }
      if (std::string(layout) == "pile on plate") {
        EXPECT_EQ(grid.large_count(), 1u);
      }
    }
  }
}

// The grid reads boxes in place from larger records (BoxView::of, as the world reads its blocks'
// boxes): the same pairs as from the vectors of corners. Oracle: brute force over the vectors
// (which keeps the pairs with (i + j) % 7 != 0, as `want` here).
TEST(BroadPhase, GridReadsBoxesInPlaceFromRecords) {
  struct Record {
    int tag = 0;  // other members around the corners, as in a block
    Eigen::Vector3d lo, hi;
    double more[3] = {0, 0, 0};
  };
  Rng rng(5);
  std::vector<Eigen::Vector3d> centres;
  for (int i = 0; i < 500; ++i)
    centres.emplace_back(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -1, 1));
  std::vector<Eigen::Vector3d> lo, hi;
  boxes(centres, rng, lo, hi);
  std::vector<Record> records(lo.size());
  for (std::size_t i = 0; i < lo.size(); ++i) {
    records[i].tag = static_cast<int>(i);
    records[i].lo = lo[i];
    records[i].hi = hi[i];
  }
  const Pairs expected = brute_force(lo, hi);
  ASSERT_FALSE(expected.empty());
  UniformGrid grid;
  for (int threads : {1, 2}) {
    Pairs found;
    grid.find_pairs(
        BoxView::of(records.data(), records.size(), &Record::lo, &Record::hi),
        [](int i, int j) { return (i + j) % 7 != 0; }, found, threads);
    EXPECT_EQ(found, expected) << "threads " << threads;
  }
}

// The grid's pairs by ranges of boxes (as a one-process step reads them, world_pairs.cpp): each
// range [begin, end) gets exactly its boxes' pairs, sorted, and the ranges in order are the
// list of find_pairs. Oracle: brute force (with `want` as above). Over 1,000 boxes, four ranges
// and a short last one; on 1 and 3 threads (ranges taken concurrently). With a large box (a
// plate under the others) the method declines and calls nothing.
TEST(BroadPhase, GridPairsByRangeAreTheSortedListCutAtTheRanges) {
  Rng rng(11);
  std::vector<Eigen::Vector3d> centres;
  for (int i = 0; i < 1000; ++i)
    centres.emplace_back(uniform(rng, -4, 4), uniform(rng, -4, 4), uniform(rng, -2, 2));
  std::vector<Eigen::Vector3d> lo, hi;
  boxes(centres, rng, lo, hi);
  const Pairs expected = brute_force(lo, hi);
  ASSERT_GT(expected.size(), 1000u);
  const auto want = [](int i, int j) { return (i + j) % 7 != 0; };
  const std::int64_t size = UniformGrid::kRangeBoxes;
  const std::size_t ranges = (lo.size() + size - 1) / size;
  UniformGrid grid;
  for (int threads : {1, 3}) {
    std::vector<Pairs> by_range(ranges);
    std::vector<int> calls(ranges, 0);
    const bool taken = grid.find_pairs_by_range(
        BoxView(lo, hi), want,
        [&](std::int64_t begin, std::int64_t end, const Pairs& pairs) {
          const auto r = static_cast<std::size_t>(begin / size);
          EXPECT_EQ(begin % size, 0);
          EXPECT_EQ(end,
                    std::min<std::int64_t>(begin + size, static_cast<std::int64_t>(lo.size())));
          for (const auto& [i, j] : pairs) {
            EXPECT_TRUE(i >= begin && i < end) << "pair (" << i << ", " << j << ")";
          }
          by_range[r] = pairs;
          ++calls[r];  // each range once: one thread writes its entry
        },
        threads);
    ASSERT_TRUE(taken);
    Pairs joined;
    for (std::size_t r = 0; r < ranges; ++r) {
      EXPECT_EQ(calls[r], 1) << "range " << r;
      joined.insert(joined.end(), by_range[r].begin(), by_range[r].end());
    }
    EXPECT_EQ(joined, expected) << "threads " << threads;
  }
  lo[7] = Eigen::Vector3d(-5, -5, -3);
  hi[7] = Eigen::Vector3d(5, 5, -2.5);
  int calls = 0;
  EXPECT_FALSE(grid.find_pairs_by_range(
      BoxView(lo, hi), want, [&](std::int64_t, std::int64_t, const Pairs&) { ++calls; }, 2));
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace blockdem
