// Sweep and prune: ordering of box starts along x.
#include "blockdem/collision/broad_phase.hpp"

#include <numeric>

namespace blockdem {

void SweepAndPrune::update_order(const std::vector<Eigen::Vector3d>& box_min) {
  if (order_.size() != box_min.size()) {
    order_.resize(box_min.size());
    std::iota(order_.begin(), order_.end(), 0);
  }
  // Insertion sort: nearly sorted input from the previous step costs O(n).
  for (std::size_t k = 1; k < order_.size(); ++k) {
    const int v = order_[k];
    const double key = box_min[v].x();
    std::size_t m = k;
    while (m > 0 && box_min[order_[m - 1]].x() > key) {
      order_[m] = order_[m - 1];
      --m;
    }
    order_[m] = v;
  }
}

}  // namespace blockdem
