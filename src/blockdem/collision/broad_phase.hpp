// Broad phase: candidate pairs from axis-aligned bounding boxes by sweep and prune.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace blockdem {

/// Axis-aligned boxes read in place: box i's min and max corners are three doubles each, at
/// byte offset i * stride from `min` and `max`. The boxes of a vector of corners (stride 24
/// bytes), or those kept in larger records (stride the record's size), without a copy of
/// every box.
struct BoxView {
  const unsigned char* min = nullptr;
  const unsigned char* max = nullptr;
  std::size_t stride = 0;  ///< (bytes)
  std::size_t count = 0;

  BoxView() = default;
  /// The boxes of two vectors of corners, one box per entry.
  BoxView(const std::vector<Eigen::Vector3d>& box_min, const std::vector<Eigen::Vector3d>& box_max)
      : min(reinterpret_cast<const unsigned char*>(box_min.data())),
        max(reinterpret_cast<const unsigned char*>(box_max.data())),
        stride(sizeof(Eigen::Vector3d)),
        count(box_min.size()) {}
  /// The boxes of `n` records of `Record` at `first`, whose corners are the members `lo`, `hi`.
  template <class Record>
  static BoxView of(const Record* first, std::size_t n, Eigen::Vector3d Record::*lo,
                    Eigen::Vector3d Record::*hi) {
    BoxView v;
    if (n == 0) return v;
    v.min = reinterpret_cast<const unsigned char*>((first->*lo).data());
    v.max = reinterpret_cast<const unsigned char*>((first->*hi).data());
    v.stride = sizeof(Record);
    v.count = n;
    return v;
  }

  std::size_t size() const { return count; }
  Eigen::Map<const Eigen::Vector3d> lo(std::size_t i) const {
    return Eigen::Map<const Eigen::Vector3d>(reinterpret_cast<const double*>(min + i * stride));
  }
  Eigen::Map<const Eigen::Vector3d> hi(std::size_t i) const {
    return Eigen::Map<const Eigen::Vector3d>(reinterpret_cast<const double*>(max + i * stride));
  }
};

/// Sorts candidate pairs (i < j) by (i, j) in O(pairs + bodies): a counting sort on i, then each
/// i's few j (a body with many pairs, such as a base plate, by std::sort). Keeps its buffers
/// until release().
class PairSorter {
 public:
  /// Pairs already grouped by i (a one-thread sweep in body order) are sorted in place, without
  /// the scratch list.
  void sort(std::vector<std::pair<int, int>>& pairs, std::size_t bodies);
  /// The pairs of `parts` (each thread's list, in any order), sorted into `pairs`; each part is
  /// freed once its pairs are placed, so that the lists and the sorted pairs are not all whole
  /// in memory with a scratch list besides.
  void sort_parts(std::vector<std::vector<std::pair<int, int>>>& parts,
                  std::vector<std::pair<int, int>>& pairs, std::size_t bodies);
  /// Sorts one body's pairs [begin, end) (all with the same i) by j: mostly a few (insertion
  /// sort), a large body's (a base plate) many.
  static void sort_one_body(std::vector<std::pair<int, int>>& pairs, std::size_t begin,
                            std::size_t end);
  /// Frees the buffers (a large scene's scratch list is as long as its list of pairs).
  void release() {
    std::vector<std::pair<int, int>>().swap(scratch_);
    std::vector<std::size_t>().swap(starts_);
  }

 private:
  std::vector<std::pair<int, int>> scratch_;
  std::vector<std::size_t> starts_;
};

/// Sweep and prune (Baraff 1992) along the world axis on which the box centres spread most, so
/// that a tall column or a long wall is swept along its length (sweeping across it would test
/// every pair); a candidate must overlap on the other two axes as well. The order of box starts
/// is kept between calls and repaired by insertion sort, which costs O(n) when blocks move little
/// per step; it is rebuilt when the axis changes, which needs the spread on the new axis to exceed
/// the current one's by a quarter (no flip-flopping). The sweep runs on `threads` threads; the
/// pairs come out sorted by (i, j) whatever the number of threads or the sweep's internal order.
class SweepAndPrune {
 public:
  /// Pairs (i < j) whose boxes overlap on all three axes, for which `want(i, j)` is true, sorted
  /// by (i, j). Boxes are given as min/max corners, one per body (m). `want` must be safe to call
  /// from several threads at once.
  template <class Want>
  void find_pairs(const std::vector<Eigen::Vector3d>& box_min,
                  const std::vector<Eigen::Vector3d>& box_max, Want&& want,
                  std::vector<std::pair<int, int>>& pairs, int threads = 1);

  /// The axis of the last sweep (0, 1, 2 for x, y, z).
  int axis() const { return axis_; }

 private:
  void update_order(const std::vector<Eigen::Vector3d>& box_min,
                    const std::vector<Eigen::Vector3d>& box_max);
  std::vector<int> order_;
  int axis_ = 0;
  std::vector<std::vector<std::pair<int, int>>> chunks_;  // per-thread output of the sweep
  PairSorter sorter_;
};

template <class Want>
void SweepAndPrune::find_pairs(const std::vector<Eigen::Vector3d>& box_min,
                               const std::vector<Eigen::Vector3d>& box_max, Want&& want,
                               std::vector<std::pair<int, int>>& pairs, int threads) {
  pairs.clear();
  update_order(box_min, box_max);
  const int s = axis_, t = (axis_ + 1) % 3, u = (axis_ + 2) % 3;  // sweep axis, then the others
  const std::int64_t n = static_cast<std::int64_t>(order_.size());
  if (threads < 1) threads = 1;
  chunks_.resize(static_cast<std::size_t>(threads));
  for (auto& c : chunks_) c.clear();
  // Each thread sweeps its share of box starts into its own list; the lists are joined and sorted
  // afterwards, so that the result does not depend on how the work was shared. One thread runs
  // the body outside any region (its work-sharing loop then runs every iteration; a team of one
  // would still cost a futex call at its end).
  const auto sweep = [&] {
#ifdef _OPENMP
    std::vector<std::pair<int, int>>& out = chunks_[static_cast<std::size_t>(omp_get_thread_num())];
#else
    std::vector<std::pair<int, int>>& out = chunks_[0];
#endif
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t k = 0; k < n; ++k) {
      const int i = order_[static_cast<std::size_t>(k)];
      const double reach = box_max[i][s];
      for (std::int64_t m = k + 1; m < n; ++m) {
        const int j = order_[static_cast<std::size_t>(m)];
        if (box_min[j][s] > reach) break;
        if (box_min[j][t] > box_max[i][t] || box_min[i][t] > box_max[j][t]) continue;
        if (box_min[j][u] > box_max[i][u] || box_min[i][u] > box_max[j][u]) continue;
        const int a = std::min(i, j), b = std::max(i, j);
        if (want(a, b)) out.emplace_back(a, b);
      }
    }
  };
  if (threads > 1 && n > 256) {
#pragma omp parallel num_threads(threads)
    sweep();
  } else {
    sweep();
  }
  for (const auto& c : chunks_) pairs.insert(pairs.end(), c.begin(), c.end());
  sorter_.sort(pairs, order_.size());
}

}  // namespace blockdem
