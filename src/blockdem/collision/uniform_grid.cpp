// Uniform grid broad phase: cell size, large boxes, and the filing of boxes in cells.
#include "blockdem/collision/uniform_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace blockdem {

void UniformGrid::build(const BoxView& boxes) {
  const std::size_t n = boxes.size();
  // Ordinary boxes: largest edge at most twice the median largest edge.
  std::vector<double> edge(n);
  for (std::size_t i = 0; i < n; ++i) edge[i] = (boxes.hi(i) - boxes.lo(i)).maxCoeff();
  std::vector<double> sorted = edge;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2),
                   sorted.end());
  const double limit = 2.0 * sorted[n / 2];
  ordinary_.assign(n, 0);
  large_.clear();
  cell_ = 0.0;
  origin_.setConstant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d top = -origin_;
  for (std::size_t i = 0; i < n; ++i) {
    // Non-finite boxes go to the large list, where they are compared (and rejected) directly.
    if (edge[i] <= limit && boxes.lo(i).allFinite() && boxes.hi(i).allFinite()) {
      ordinary_[i] = 1;
      cell_ = std::max(cell_, edge[i]);
      origin_ = origin_.cwiseMin(boxes.lo(i));
      top = top.cwiseMax(boxes.lo(i));
    } else {
      large_.push_back(static_cast<int>(i));
    }
  }
  bodies_.clear();
  if (large_.size() == n) return;
  if (!(cell_ > 0.0)) cell_ = 1.0;  // points only: any cell size works
  // Cell coordinates of the min corners.
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) {
    dims_[a] = static_cast<std::int64_t>((top[a] - origin_[a]) / cell_) + 1;
    cells *= static_cast<double>(dims_[a]);
  }
  // A dense cell array when it is not much larger than the number of boxes, else sorted keys.
  dense_ = cells <= 8.0 * static_cast<double>(n) + 1024.0;
  if (!dense_ && cells > 9e18) {
    // Too many cells for 64-bit keys (boxes spread over 1e6 cell sizes in every direction).
    cell_ = std::max(cell_, (top - origin_).maxCoeff() / 1e6);
    for (int a = 0; a < 3; ++a)
      dims_[a] = static_cast<std::int64_t>((top[a] - origin_[a]) / cell_) + 1;
  }
  std::vector<std::uint64_t> body_key(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!ordinary_[i]) continue;
    const auto lo = boxes.lo(i);
    body_key[i] = key(cell_of(lo[0], 0), cell_of(lo[1], 1), cell_of(lo[2], 2));
  }
  if (dense_) {
    // Counting sort of the boxes by cell.
    const std::size_t m = static_cast<std::size_t>(cells);
    cell_start_.assign(m + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (ordinary_[i]) ++cell_start_[body_key[i] + 1];
    }
    for (std::size_t k = 0; k < m; ++k) cell_start_[k + 1] += cell_start_[k];
    bodies_.resize(cell_start_[m]);
    std::vector<std::size_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      if (ordinary_[i]) bodies_[fill[body_key[i]]++] = static_cast<int>(i);
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      if (ordinary_[i]) bodies_.push_back(static_cast<int>(i));
    }
    std::sort(bodies_.begin(), bodies_.end(), [&](int a, int b) {
      return body_key[static_cast<std::size_t>(a)] < body_key[static_cast<std::size_t>(b)] ||
             (body_key[static_cast<std::size_t>(a)] == body_key[static_cast<std::size_t>(b)] &&
              a < b);
    });
    keys_.resize(bodies_.size());
    for (std::size_t k = 0; k < bodies_.size(); ++k)
      keys_[k] = body_key[static_cast<std::size_t>(bodies_[k])];
  }
}

void UniformGrid::release() {
  std::vector<std::uint8_t>().swap(ordinary_);
  std::vector<std::size_t>().swap(cell_start_);
  std::vector<std::uint64_t>().swap(keys_);
  std::vector<int>().swap(bodies_);
  chunks_.clear();
  sorter_.release();
}

std::pair<std::size_t, std::size_t> UniformGrid::cell_range(std::uint64_t k) const {
  if (dense_) return {cell_start_[k], cell_start_[k + 1]};
  const auto lo = std::lower_bound(keys_.begin(), keys_.end(), k);
  const auto hi = std::upper_bound(lo, keys_.end(), k);
  return {static_cast<std::size_t>(lo - keys_.begin()),
          static_cast<std::size_t>(hi - keys_.begin())};
}

}  // namespace blockdem
