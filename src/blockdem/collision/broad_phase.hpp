// Broad phase: candidate pairs from axis-aligned bounding boxes by sweep and prune.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

namespace blockdem {

/// Sweep and prune along x (Baraff 1992): the order of box starts is kept between calls and
/// repaired by insertion sort, which costs O(n) when blocks move little per step.
class SweepAndPrune {
 public:
  /// Pairs (i < j) whose boxes overlap on all three axes, for which `want(i, j)` is true.
  /// Boxes are given as min/max corners, one per body (m).
  template <class Want>
  void find_pairs(const std::vector<Eigen::Vector3d>& box_min, const std::vector<Eigen::Vector3d>& box_max,
                  Want&& want, std::vector<std::pair<int, int>>& pairs);

 private:
  void update_order(const std::vector<Eigen::Vector3d>& box_min);
  std::vector<int> order_;
};

template <class Want>
void SweepAndPrune::find_pairs(const std::vector<Eigen::Vector3d>& box_min,
                               const std::vector<Eigen::Vector3d>& box_max, Want&& want,
                               std::vector<std::pair<int, int>>& pairs) {
  pairs.clear();
  update_order(box_min);
  const std::size_t n = order_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const int i = order_[k];
    const double reach = box_max[i].x();
    for (std::size_t m = k + 1; m < n; ++m) {
      const int j = order_[m];
      if (box_min[j].x() > reach) break;
      if (box_min[j].y() > box_max[i].y() || box_min[i].y() > box_max[j].y()) continue;
      if (box_min[j].z() > box_max[i].z() || box_min[i].z() > box_max[j].z()) continue;
      const int a = std::min(i, j), b = std::max(i, j);
      if (want(a, b)) pairs.emplace_back(a, b);
    }
  }
}

}  // namespace blockdem
