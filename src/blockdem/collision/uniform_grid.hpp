// Broad phase for wide 3D scenes: a uniform grid of cells the size of the largest ordinary box.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "blockdem/collision/broad_phase.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace blockdem {

/// Uniform grid broad phase (spatial hashing; e.g. Ericson 2005, Real-Time Collision Detection,
/// section 7.1). Boxes no larger than twice the median box size are "ordinary": each is filed in
/// the one cell that holds its min corner, with cells as large as the largest ordinary box, so a
/// box only needs to look at the 3 x 3 x 3 cells at and below its own. The few larger boxes (a
/// base plate, a wall) are tested against every box. The cost is O(n) per call for similar-sized
/// blocks in any arrangement (a 1D sweep costs O(n^1.5) for a wide 2D or 3D pile). The cells are
/// rebuilt on every call (a counting sort over a dense cell array, or a sort of cell keys when the
/// boxes are too sparse for one); the pairs come out sorted by (i, j) for any number of threads.
class UniformGrid {
 public:
  /// Pairs (i < j) whose boxes overlap on all three axes (touching counts), for which
  /// `want(i, j)` is true, sorted by (i, j). `want` must be safe to call from several threads.
  /// The grid's buffers live only for the call: at the size of a large scene they would
  /// otherwise stay allocated through the rest of a step (about 80 bytes per box).
  template <class Want>
  void find_pairs(const BoxView& boxes, Want&& want, std::vector<std::pair<int, int>>& pairs,
                  int threads = 1);
  template <class Want>
  void find_pairs(const std::vector<Eigen::Vector3d>& box_min,
                  const std::vector<Eigen::Vector3d>& box_max, Want&& want,
                  std::vector<std::pair<int, int>>& pairs, int threads = 1) {
    find_pairs(BoxView(box_min, box_max), std::forward<Want>(want), pairs, threads);
  }

  /// The pairs of find_pairs without a list of them all: the boxes are taken in ranges of
  /// consecutive indices [begin, end), and `take(begin, end, pairs)` receives each range's pairs
  /// (i in [begin, end), j > i), sorted by (i, j), so that the ranges in increasing order give
  /// find_pairs' list. `take` runs on the thread that found the range, several at once and in no
  /// set order; its `pairs` live until it returns. Only ordinary boxes come in ranges: where
  /// there is a large box this returns false without calling `take` (use find_pairs).
  template <class Want, class Take>
  bool find_pairs_by_range(const BoxView& boxes, Want&& want, Take&& take, int threads = 1);
  /// The boxes of one range of find_pairs_by_range (the last range may be shorter).
  static constexpr std::int64_t kRangeBoxes = 256;

  double cell_size() const { return cell_; }                 ///< (m)
  std::size_t large_count() const { return large_.size(); }  ///< boxes tested against all
  bool dense() const { return dense_; }                      ///< cell array, not keys

 private:
  /// Files the ordinary boxes in cells; returns false when there are no boxes.
  void build(const BoxView& boxes);
  /// Frees the buffers filled by build() and the pair lists.
  void release();
  std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<std::uint64_t>(x + dims_[0] * (y + dims_[1] * z));
  }
  /// The cell coordinate along axis a of a box's min corner at x (computed where it is needed:
  /// kept, three per box, they were a quarter of the grid's memory).
  std::int64_t cell_of(double x, int a) const {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>((x - origin_[a]) / cell_), 0,
                                    dims_[a] - 1);
  }
  /// Range [begin, end) in bodies_ of the cell with this key.
  std::pair<std::size_t, std::size_t> cell_range(std::uint64_t k) const;
  /// Whether boxes i and j overlap on all three axes (touching counts).
  static bool overlap(const BoxView& boxes, int i, int j) {
    const auto ilo = boxes.lo(static_cast<std::size_t>(i)),
               ihi = boxes.hi(static_cast<std::size_t>(i));
    const auto jlo = boxes.lo(static_cast<std::size_t>(j)),
               jhi = boxes.hi(static_cast<std::size_t>(j));
    return !(jlo.x() > ihi.x() || ilo.x() > jhi.x() || jlo.y() > ihi.y() || ilo.y() > jhi.y() ||
             jlo.z() > ihi.z() || ilo.z() > jhi.z());
  }
  /// Appends ordinary box i's pairs (i, j > i) with ordinary boxes for which want(i, j).
  template <class Want>
  void ordinary_pairs(const BoxView& boxes, std::int64_t i, Want& want,
                      std::vector<std::pair<int, int>>& out) const;

  double cell_ = 0.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::int64_t dims_[3] = {0, 0, 0};
  bool dense_ = true;
  std::vector<std::uint8_t> ordinary_;   // 1 for an ordinary box
  std::vector<int> large_;               // the other boxes
  std::vector<std::size_t> cell_start_;  // dense: start of each cell in bodies_ (+ end)
  std::vector<std::uint64_t> keys_;      // sparse: sorted cell key of each bodies_ entry
  std::vector<int> bodies_;              // ordinary boxes grouped by cell
  std::vector<std::vector<std::pair<int, int>>> chunks_;
  PairSorter sorter_;
};

template <class Want>
void UniformGrid::find_pairs(const BoxView& boxes, Want&& want,
                             std::vector<std::pair<int, int>>& pairs, int threads) {
  pairs.clear();
  const std::int64_t n = static_cast<std::int64_t>(boxes.size());
  if (n == 0) return;
  build(boxes);
  if (threads < 1) threads = 1;
  // One thread writes straight into `pairs` (no second list of every pair to keep between
  // calls); several write their own lists, joined in thread order.
  chunks_.resize(threads > 1 ? static_cast<std::size_t>(threads) : 0);
  for (auto& c : chunks_) c.clear();
  // The region's body, run by each thread of a team, or alone outside any region for one thread
  // (its work-sharing loops then run every iteration; a team of one would still cost a futex
  // call at its end).
  const auto sweep = [&] {
#ifdef _OPENMP
    std::vector<std::pair<int, int>>& out =
        threads > 1 ? chunks_[static_cast<std::size_t>(omp_get_thread_num())] : pairs;
#else
    std::vector<std::pair<int, int>>& out = threads > 1 ? chunks_[0] : pairs;
#endif
    // Ordinary against ordinary (ordinary_pairs).
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < n; ++i) {
      if (ordinary_[static_cast<std::size_t>(i)]) ordinary_pairs(boxes, i, want, out);
    }
    // Large boxes against every other box (each large-large pair once).
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t l = 0; l < static_cast<std::int64_t>(large_.size()); ++l) {
      const int i = large_[static_cast<std::size_t>(l)];
      for (int j = 0; j < static_cast<int>(n); ++j) {
        if (j == i || (!ordinary_[static_cast<std::size_t>(j)] && j < i)) continue;
        const int a = std::min(i, j), b = std::max(i, j);
        if (overlap(boxes, a, b) && want(a, b)) out.emplace_back(a, b);
      }
    }
  };
  if (threads > 1 && n > 256) {
#pragma omp parallel num_threads(threads)
    sweep();
  } else {
    sweep();
  }
  if (threads > 1) {
    sorter_.sort_parts(chunks_, pairs, static_cast<std::size_t>(n));
  } else {
    sorter_.sort(pairs, static_cast<std::size_t>(n));
  }
  release();
}

template <class Want>
void UniformGrid::ordinary_pairs(const BoxView& boxes, std::int64_t i, Want& want,
                                 std::vector<std::pair<int, int>>& out) const {
  // Box i looks at the cells whose boxes can reach it (their min corner at most one cell below
  // its own min corner, at most its max corner) and keeps j > i.
  const auto ilo = boxes.lo(static_cast<std::size_t>(i)),
             ihi = boxes.hi(static_cast<std::size_t>(i));
  const std::int64_t c[3] = {cell_of(ilo[0], 0), cell_of(ilo[1], 1), cell_of(ilo[2], 2)};
  std::int64_t hi[3];
  for (int a = 0; a < 3; ++a) {
    hi[a] = std::min<std::int64_t>(dims_[a] - 1,
                                   static_cast<std::int64_t>((ihi[a] - origin_[a]) / cell_));
  }
  for (std::int64_t z = std::max<std::int64_t>(0, c[2] - 1); z <= hi[2]; ++z) {
    for (std::int64_t y = std::max<std::int64_t>(0, c[1] - 1); y <= hi[1]; ++y) {
      for (std::int64_t x = std::max<std::int64_t>(0, c[0] - 1); x <= hi[0]; ++x) {
        const auto [begin, end] = cell_range(key(x, y, z));
        for (std::size_t k = begin; k < end; ++k) {
          const int j = bodies_[k];
          if (j <= i) continue;
          if (overlap(boxes, static_cast<int>(i), j) && want(static_cast<int>(i), j))
            out.emplace_back(static_cast<int>(i), j);
        }
      }
    }
  }
}

template <class Want, class Take>
bool UniformGrid::find_pairs_by_range(const BoxView& boxes, Want&& want, Take&& take, int threads) {
  const std::int64_t n = static_cast<std::int64_t>(boxes.size());
  if (n == 0) return true;
  build(boxes);
  if (!large_.empty()) {
    release();
    return false;
  }
  if (threads < 1) threads = 1;
  const std::int64_t ranges = (n + kRangeBoxes - 1) / kRangeBoxes;
  const auto sweep = [&] {
    std::vector<std::pair<int, int>> out;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t r = 0; r < ranges; ++r) {
      const std::int64_t begin = r * kRangeBoxes, end = std::min(n, begin + kRangeBoxes);
      out.clear();
      for (std::int64_t i = begin; i < end; ++i) {
        const std::size_t first = out.size();
        ordinary_pairs(boxes, i, want, out);
        PairSorter::sort_one_body(out, first, out.size());  // box i's pairs by j
      }
      take(begin, end, static_cast<const std::vector<std::pair<int, int>>&>(out));
    }
  };
  if (threads > 1 && ranges > 1) {
#pragma omp parallel num_threads(threads)
    sweep();
  } else {
    sweep();
  }
  release();
  return true;
}

}  // namespace blockdem
