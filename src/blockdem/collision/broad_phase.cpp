// Sweep and prune: choice of the sweep axis and ordering of box starts along it.
#include "blockdem/collision/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace blockdem {

void SweepAndPrune::update_order(const std::vector<Eigen::Vector3d>& box_min,
                                 const std::vector<Eigen::Vector3d>& box_max) {
  const std::size_t n = box_min.size();
  // Spread of the box centres per axis: the sum of squared deviations from their mean.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) mean += 0.5 * (box_min[i] + box_max[i]);
  if (n > 0) mean /= static_cast<double>(n);
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    spread += (0.5 * (box_min[i] + box_max[i]) - mean).cwiseAbs2();
  }
  int best = axis_;
  for (int k = 0; k < 3; ++k) {
    if (spread[k] > 1.25 * spread[best]) best = k;
  }
  const bool rebuild = order_.size() != n || best != axis_;
  axis_ = best;
  const int s = axis_;
  if (rebuild) {
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    std::sort(order_.begin(), order_.end(), [&](int a, int b) {
      return box_min[a][s] < box_min[b][s] || (box_min[a][s] == box_min[b][s] && a < b);
    });
    return;
  }
  // Insertion sort: nearly sorted input from the previous step costs O(n).
  for (std::size_t k = 1; k < n; ++k) {
    const int v = order_[k];
    const double key = box_min[v][s];
    std::size_t m = k;
    while (m > 0 && box_min[order_[m - 1]][s] > key) {
      order_[m] = order_[m - 1];
      --m;
    }
    order_[m] = v;
  }
}

namespace {

// Sorts each body's pairs by j in place: body i's pairs are [ends[i - 1], ends[i]) (from 0 for
// body 0).
void sort_each_body(std::vector<std::pair<int, int>>& pairs, const std::size_t* ends,
                    std::size_t bodies) {
  std::size_t begin = 0;
  for (std::size_t i = 0; i < bodies; ++i) {
    PairSorter::sort_one_body(pairs, begin, ends[i]);
    begin = ends[i];
  }
}

}  // namespace

void PairSorter::sort_one_body(std::vector<std::pair<int, int>>& pairs, std::size_t begin,
                               std::size_t end) {
  if (end - begin > 32) {
    std::sort(pairs.begin() + static_cast<std::ptrdiff_t>(begin),
              pairs.begin() + static_cast<std::ptrdiff_t>(end));
    return;
  }
  for (std::size_t k = begin + 1; k < end; ++k) {
    const auto v = pairs[k];
    std::size_t m = k;
    while (m > begin && pairs[m - 1].second > v.second) {
      pairs[m] = pairs[m - 1];
      --m;
    }
    pairs[m] = v;
  }
}

void PairSorter::sort(std::vector<std::pair<int, int>>& pairs, std::size_t bodies) {
  // Counting sort on the first body: starts_[i] is where body i's pairs begin.
  starts_.assign(bodies + 1, 0);
  bool grouped = true;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    ++starts_[static_cast<std::size_t>(pairs[k].first) + 1];
    grouped = grouped && (k == 0 || pairs[k - 1].first <= pairs[k].first);
  }
  for (std::size_t i = 0; i < bodies; ++i) starts_[i + 1] += starts_[i];
  if (grouped) {
    // starts_[i + 1] is the end of body i's pairs, already in place.
    sort_each_body(pairs, starts_.data() + 1, bodies);
    return;
  }
  scratch_.resize(pairs.size());
  for (const auto& p : pairs) scratch_[starts_[static_cast<std::size_t>(p.first)]++] = p;
  // starts_[i] now holds the end of body i's pairs.
  sort_each_body(scratch_, starts_.data(), bodies);
  pairs.swap(scratch_);
}

void PairSorter::sort_parts(std::vector<std::vector<std::pair<int, int>>>& parts,
                            std::vector<std::pair<int, int>>& pairs, std::size_t bodies) {
  starts_.assign(bodies + 1, 0);
  std::size_t total = 0;
  for (const auto& part : parts) {
    total += part.size();
    for (const auto& p : part) ++starts_[static_cast<std::size_t>(p.first) + 1];
  }
  for (std::size_t i = 0; i < bodies; ++i) starts_[i + 1] += starts_[i];
  pairs.resize(total);
  for (auto& part : parts) {
    for (const auto& p : part) pairs[starts_[static_cast<std::size_t>(p.first)]++] = p;
    std::vector<std::pair<int, int>>().swap(part);
  }
  // starts_[i] now holds the end of body i's pairs.
  sort_each_body(pairs, starts_.data(), bodies);
}

}  // namespace blockdem
