// Broad phase: candidate pairs from axis-aligned bounding boxes by sweep and prune.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

namespace blockdem {

/// Sweep and prune (Baraff 1992) along the world axis on which the box centres spread most, so
/// that a tall column or a long wall is swept along its length (sweeping across it would test
/// every pair). The order of box starts is kept between calls and repaired by insertion sort,
/// which costs O(n) when blocks move little per step; it is rebuilt when the axis changes, which
/// needs the spread on the new axis to exceed the current one's by a quarter (no flip-flopping).
class SweepAndPrune {
 public:
  /// Pairs (i < j) whose boxes overlap on all three axes, for which `want(i, j)` is true, in a
  /// deterministic order. Boxes are given as min/max corners, one per body (m).
  template <class Want>
  void find_pairs(const std::vector<Eigen::Vector3d>& box_min,
                  const std::vector<Eigen::Vector3d>& box_max, Want&& want,
                  std::vector<std::pair<int, int>>& pairs);

  /// The axis of the last sweep (0, 1, 2 for x, y, z).
  int axis() const { return axis_; }

 private:
  void update_order(const std::vector<Eigen::Vector3d>& box_min,
                    const std::vector<Eigen::Vector3d>& box_max);
  std::vector<int> order_;
  int axis_ = 0;
};

template <class Want>
void SweepAndPrune::find_pairs(const std::vector<Eigen::Vector3d>& box_min,
                               const std::vector<Eigen::Vector3d>& box_max, Want&& want,
                               std::vector<std::pair<int, int>>& pairs) {
  pairs.clear();
  update_order(box_min, box_max);
  const int s = axis_, t = (axis_ + 1) % 3, u = (axis_ + 2) % 3;  // sweep axis, then the others
  const std::size_t n = order_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const int i = order_[k];
    const double reach = box_max[i][s];
    for (std::size_t m = k + 1; m < n; ++m) {
      const int j = order_[m];
      if (box_min[j][s] > reach) break;
      if (box_min[j][t] > box_max[i][t] || box_min[i][t] > box_max[j][t]) continue;
      if (box_min[j][u] > box_max[i][u] || box_min[i][u] > box_max[j][u]) continue;
      const int a = std::min(i, j), b = std::max(i, j);
      if (want(a, b)) pairs.emplace_back(a, b);
    }
  }
}

}  // namespace blockdem
