// Recursive coordinate bisection (Berger & Bokhari 1987, IEEE Trans. Computers C-36(5):570-580:
// cuts through the weighted median normal to a coordinate axis; here the longest axis of the
// part's bounding box, and the ratio floor(K/2) : ceil(K/2) for any number of parts K).
#include "blockdem/parallel/rcb.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace blockdem {
namespace {

void bisect(std::span<const Eigen::Vector3d> points, std::span<const double> weights,
            std::vector<int>& ids, std::size_t begin, std::size_t end, int first_part, int parts,
            std::vector<int>& part) {
  if (parts == 1) {
    for (std::size_t i = begin; i < end; ++i) part[static_cast<std::size_t>(ids[i])] = first_part;
    return;
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (std::size_t i = begin; i < end; ++i) {
    lo = lo.cwiseMin(points[static_cast<std::size_t>(ids[i])]);
    hi = hi.cwiseMax(points[static_cast<std::size_t>(ids[i])]);
  }
  Eigen::Index axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::sort(ids.begin() + static_cast<std::ptrdiff_t>(begin),
            ids.begin() + static_cast<std::ptrdiff_t>(end), [&](int p, int q) {
              const double xp = points[static_cast<std::size_t>(p)][axis];
              const double xq = points[static_cast<std::size_t>(q)][axis];
              return xp < xq || (xp == xq && p < q);
            });
  const int left_parts = parts / 2;
  double total = 0.0;
  for (std::size_t i = begin; i < end; ++i) total += weights[static_cast<std::size_t>(ids[i])];
  const double target = total * left_parts / parts;
  // The cut: the first point whose running weight reaches the target, keeping at least one point
  // per part on each side.
  const std::size_t min_cut = begin + static_cast<std::size_t>(left_parts);
  const std::size_t max_cut = end - static_cast<std::size_t>(parts - left_parts);
  std::size_t cut = begin;
  double running = 0.0;
  while (cut < end && running + 0.5 * weights[static_cast<std::size_t>(ids[cut])] < target) {
    running += weights[static_cast<std::size_t>(ids[cut])];
    ++cut;
  }
  cut = std::clamp(cut, min_cut, max_cut);
  bisect(points, weights, ids, begin, cut, first_part, left_parts, part);
  bisect(points, weights, ids, cut, end, first_part + left_parts, parts - left_parts, part);
}

}  // namespace

std::vector<int> recursive_coordinate_bisection(std::span<const Eigen::Vector3d> points,
                                                std::span<const double> weights, int parts) {
  if (points.size() != weights.size())
    throw std::invalid_argument("recursive_coordinate_bisection: one weight per point expected");
  if (parts < 1) throw std::invalid_argument("recursive_coordinate_bisection: parts must be >= 1");
  if (static_cast<std::size_t>(parts) > points.size())
    throw std::invalid_argument("cannot split " + std::to_string(points.size()) + " blocks over " +
                                std::to_string(parts) +
                                " processes: need at least one block per process");
  for (double w : weights) {
    if (!(w > 0.0) || !std::isfinite(w))
      throw std::invalid_argument("recursive_coordinate_bisection: weights must be positive");
  }
  std::vector<int> ids(points.size());
  std::iota(ids.begin(), ids.end(), 0);
  std::vector<int> part(points.size(), 0);
  bisect(points, weights, ids, 0, ids.size(), 0, parts, part);
  return part;
}

double partition_imbalance(std::span<const double> weights, const std::vector<int>& part,
                           int parts) {
  std::vector<double> sum(static_cast<std::size_t>(parts), 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    sum[static_cast<std::size_t>(part[i])] += weights[i];
    total += weights[i];
  }
  const double mean = total / parts;
  return mean > 0.0 ? *std::max_element(sum.begin(), sum.end()) / mean : 1.0;
}

}  // namespace blockdem
